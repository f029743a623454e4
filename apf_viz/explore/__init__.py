"""Exhaustive exploration of the adversary's schedules on small starts."""

# The modules are the interface: import from them (apf_viz.<package>.<module>); nothing is re-exported.
__all__: list[str] = []
