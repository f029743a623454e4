"""The API's tables are pandas DataFrames, and pandas comes with the ``notebook`` extra: where it is
missing, one line says what needed it and how to install it (the same words for every table)."""

from __future__ import annotations

from types import ModuleType

from apf_viz.core.formats import InputError

__all__ = ["pandas_for"]


def pandas_for(what: str) -> ModuleType:
    """pandas, imported when a table is first asked for (``apf-viz …`` starts without it).

    Args:
        what: what needs it, as the message says it ("sweep's table").

    Returns:
        The pandas module.

    Raises:
        InputError: pandas is not installed.
    """
    try:
        import pandas
    except ModuleNotFoundError:
        raise InputError(
            f"{what} needs pandas: pip install 'apf-viz[notebook]' "
            "(in a checkout: pip install -e '.[notebook]')"
        ) from None
    module: ModuleType = pandas
    return module
