"""Figures for papers: what the canvas shows of a run at one moment, as SVG, TikZ or PNG, in grid units.

:mod:`~apf_viz.figure.drawing` reads a :class:`~apf_viz.workbench.view_model.SessionView` into a
:class:`~apf_viz.figure.drawing.Drawing` (cells, robots in their lights' colours, the algorithm's lines
and frames, one robot's rays and the robots it cannot see, a legend); :mod:`~apf_viz.figure.svg` and
:mod:`~apf_viz.figure.tikz` write it out. No viser here.
"""

# The modules are the interface: import from them (apf_viz.<package>.<module>); nothing else is here but
# the formats, which the command line's help needs without loading a drawing.
__all__ = ["FORMATS"]

FORMATS = ("svg", "tikz", "png")
"""Every format a figure is drawn in: SVG and TikZ text, and PNG (matplotlib)."""
