"""The room at a glance (issue #58): the shared run handed to one class page and taken back, and the
presenter's list of class pages (tests/test_room_browser.py shows it in a browser)."""

from __future__ import annotations

import pytest

from apf_viz.core.formats import InputError
from apf_viz.ui.app import demo_session
from apf_viz.workbench.classroom import Classroom


def test_the_run_handed_to_one_class_page_is_its_and_the_presenters_alone_until_taken_back():
    room = Classroom(demo_session())
    room.join("projector", "presenter")
    room.join("laptop a", "class", "seat a")
    room.join("laptop b", "class", "seat b")
    assert (room.laptop("laptop a"), room.laptop("laptop b"), room.laptop("projector")) == (1, 2, None)
    assert not room.may_drive("laptop a") and not room.may_drive("laptop b")
    with pytest.raises(InputError, match="only a presenter page"):
        room.hand(2, "laptop a")  # a class page cannot hand the run to itself or another
    room.hand(1, "projector")
    assert room.may_drive("laptop a") and not room.may_drive("laptop b") and room.may_drive("projector")
    assert [p.drives for p in room.listing()] == [True, False]
    room.hand(None, "projector")
    assert not room.may_drive("laptop a")
    room.hand(2, "projector")
    room.leave("laptop b")  # the page left: the run is the presenter's again, for any page that comes next
    room.join("laptop b", "class", "seat b")
    assert not room.may_drive("laptop b") and room.laptop("laptop b") == 2  # its seat keeps its number
    with pytest.raises(InputError, match="laptop 3 is not in the room"):
        room.hand(3, "projector")
