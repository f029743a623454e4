"""Exhaustive exploration of the adversary's schedules on small starts."""
