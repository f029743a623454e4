"""The visualiser: a thin viser adapter (app, browser screens, panels, scene, broadcast, own runs) over
the viser-free workbench (:mod:`apf_viz.workbench`) and the pure core."""
