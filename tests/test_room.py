"""The room at a glance (issue #58): the shared run handed to one class page and taken back, and the
presenter's list of class pages (tests/test_room_browser.py shows it in a browser)."""

from __future__ import annotations

import pytest

from apf_viz.core.formats import InputError
from apf_viz.ui.app import demo_session


def test_the_run_handed_to_one_class_page_is_its_and_the_presenters_alone_until_taken_back():
    s = demo_session()
    s.join("projector", "presenter")
    s.join("laptop a", "class")
    s.join("laptop b", "class")
    assert not s.may_drive("laptop a") and not s.may_drive("laptop b")
    with pytest.raises(InputError, match="only a presenter page"):
        s.hand_run_to("laptop b", "laptop a")  # a class page cannot hand the run to itself or another
    s.hand_run_to("laptop a", "projector")
    assert s.may_drive("laptop a") and not s.may_drive("laptop b") and s.may_drive("projector")
    s.hand_run_to(None, "projector")
    assert not s.may_drive("laptop a")
    s.hand_run_to("laptop b", "projector")
    s.leave("laptop b")  # the page left: the run is the presenter's again, for any page that comes next
    s.join("laptop b", "class")
    assert not s.may_drive("laptop b")
    with pytest.raises(InputError, match="has left"):
        s.hand_run_to("laptop gone", "projector")
