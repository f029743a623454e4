"""The workbench: everything the visualiser does that knows no browser and no viser.

A :class:`~apf_viz.workbench.session.Session` holds the run a page shows and the commands on it (step,
time travel, drafts, files, lectures); :mod:`~apf_viz.workbench.view_model` turns it into what is drawn
and said; the run controller, screen state, editor, loader, compare, lecturer and studio are its parts;
:mod:`~apf_viz.workbench.config` builds a session from a plain config. ``figure/``, ``lecture check`` and
the exports build on this package; ``ui/`` is the viser adapter over it (app, browser screens, panels,
scene, broadcast, own runs), and nothing here imports ``ui/`` or viser (tests/test_house.py).
"""

# The modules are the interface: import from them (apf_viz.<package>.<module>); nothing is re-exported.
__all__: list[str] = []
