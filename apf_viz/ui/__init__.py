"""The visualiser: a thin viser adapter (app, browser screens, panels, scene, broadcast, own runs) over
the viser-free workbench (:mod:`apf_viz.workbench`) and the pure core."""

# The modules are the interface: import from them (apf_viz.<package>.<module>); nothing is re-exported.
__all__: list[str] = []
