"""The visualiser: a thin viser layer over the pure core (session, scene, panels, app)."""
