"""apf-viz: an interactive workbench for asynchronous opaque luminous robots on the infinite grid."""

__version__ = "0.1.0"
