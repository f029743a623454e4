"""A lecture's exported page paced like the lecture: it opens paused at stop 1, PageDown / PageUp (and
the arrow keys) go to the next or previous stop, Space still plays, and each stop's title and words are
an HTML caption over the bottom of the canvas at the projector's sizes (workbench/view_model/caption.py).

The recording (ui/page_export.py) holds the stops one after another, each from a known second; a stop is
shown by seeking viser's player to that second through its time field (the one control of its playback
bar a page can set; how it is found is one of viser's insides, kept in ui/viser_compat.py). If a release
drops that field, the page says so in its caption and plays as a slideshow (the exported page's browser
test in tests/test_lecture_projector.py holds the contract)."""

from __future__ import annotations

import html
import json
from dataclasses import asdict, dataclass

from apf_viz.ui.viser_compat import PLAYER_TIME_FIELD_JS
from apf_viz.workbench.view_model.caption import TITLE_PX, WORDS_PX
from apf_viz.workbench.view_model.legend import symbol_html


@dataclass(frozen=True)
class PageQuestion:
    """A stop's question on the page (workbench/poll.py): the reader answers (a choice, or a cell typed),
    then reveals: the page shows the run's answer and goes to the recording's second ``reveal_at``, where
    the run shows it."""

    text: str
    kind: str
    choices: tuple[tuple[str, str], ...] | None  # (value, words); None: a cell, typed as x, y
    right: tuple[str, ...]
    answer: str  # the run's answer in words
    reveal_at: float
    revealed_status: str = ""  # the state line where the run shows the answer (its stage, its event)


@dataclass(frozen=True)
class PageStop:
    """A stop on the page: the second it starts at in the recording and its words (plain text)."""

    at: float
    where: str
    title: str
    say: str
    status: str
    question: PageQuestion | None = None


_STYLE = f"""
#apf-caption {{ position: fixed; left: 10px; right: 10px; bottom: 52px; max-height: 35vh; overflow: auto;
  z-index: 5; background: rgba(255,255,255,0.94); border: 1px solid #ddd; border-radius: 4px;
  padding: 6px 12px; font: {WORDS_PX}px/1.3 -apple-system, "Segoe UI", Roboto, Arial, sans-serif;
  color: #111; }}
#apf-caption .where {{ color: #555; }}
#apf-caption .title {{ font-size: {TITLE_PX}px; font-weight: bold; line-height: 1.2; }}
#apf-caption .status {{ font-weight: bold; }}
"""

# Drives viser's player: seek by its time field (React reads a value set through the native setter and
# an input event), follow the time while playing, and take the lecture's keys before the camera does.
_SCRIPT = r"""
(function () {
  var data = JSON.parse(document.getElementById('apf-stops').textContent);
  var stops = data.stops, index = 0, shown = -1, paced = true;
  var box = document.getElementById('apf-caption');
  var field = %(field)s;
  function show(i) {
    if (i === shown) return;
    shown = i;
    var s = stops[i];
    box.innerHTML = '<div class="where">' + s.where + ' · PageDown / PageUp: next / previous stop</div>' +
      '<div class="title" data-apf="title">' + s.title + '</div>' +
      '<div data-apf="say">' + s.say + '</div>' + asked(i) + '<div class="status">' +
      (s.question && revealed[i] && s.question.revealed_status ? s.question.revealed_status : s.status) +
      '</div>' +
      (paced ? '' : '<div class="where">' + data.unpaced + '</div>');
    box.scrollTop = 0;
    document.title = data.title + ' · stop ' + (i + 1);
    told(i);
  }
  // A stop's question: the reader's answer (changed at will until the reveal), then the run's.
  var given = {}, revealed = {};
  function asked(i) {
    var q = stops[i].question;
    if (!q) return '';
    var pick = q.choices ? q.choices.map(function (c) {
      return '<button data-choice="' + c[0] + '">' + c[1] + '</button>';
    }).join(' ') : '<input data-apf="cell" placeholder="x, y" size="8"> ' +
      '<button data-apf="give-cell">Answer</button>';
    return '<div data-apf="question"><b>Question:</b> ' + q.text + '</div><div data-apf="choices">' + pick +
      ' <button data-apf="reveal">Reveal (R)</button></div><div data-apf="verdict"></div>';
  }
  function words(q, v) {
    if (!q.choices) return '(' + v.replace(',', ', ') + ') on the grid';
    for (var j = 0; j < q.choices.length; j++) if (q.choices[j][0] === v) return q.choices[j][1];
    return v;
  }
  function told(i) {
    var q = stops[i].question, out = box.querySelector('[data-apf=verdict]');
    if (!q || !out) return;
    var mine = given[i];
    if (revealed[i]) {
      var right = mine !== undefined && q.right.indexOf(mine) >= 0;
      out.innerHTML = "<b>The run's answer: " + q.answer + '.</b> ' + (mine === undefined ? '' :
        'You answered ' + words(q, mine) + ': ' + (right ? 'right.' : 'not this time.'));
    } else {
      out.innerHTML = mine === undefined ? 'Answer, then Reveal (R).' :
        'Your answer: <b>' + words(q, mine) + '</b> (change it until you reveal).';
    }
  }
  function give(v) {
    if (revealed[index]) return;
    given[index] = v;
    told(index);
  }
  function reveal() {
    var q = stops[index].question;
    if (!q) return;
    revealed[index] = true;
    told(index);
    var line = box.querySelector('.status');  // the state line follows the run to the answer's event
    if (line && q.revealed_status) line.innerHTML = q.revealed_status;
    var f = field();
    if (f) playAt(f, q.reveal_at);
  }
  box.addEventListener('click', function (e) {
    var t = e.target;
    if (t.dataset.choice !== undefined) give(t.dataset.choice);
    else if (t.dataset.apf === 'reveal') reveal();
    else if (t.dataset.apf === 'give-cell') {
      var m = /^\s*\(?\s*(-?\d+)\s*,\s*(-?\d+)\s*\)?\s*$/.exec(box.querySelector('[data-apf=cell]').value);
      if (m) give(parseInt(m[1], 10) + ',' + parseInt(m[2], 10));
      else box.querySelector('[data-apf=verdict]').textContent = 'A cell is x, y: e.g. 2, -1';
    }
  });
  function playAt(f, seconds) {  // the player's time field set to that second of the recording
    var setter = Object.getOwnPropertyDescriptor(HTMLInputElement.prototype, 'value').set;
    setter.call(f, (seconds + 0.1).toFixed(2));
    f.dispatchEvent(new Event('input', { bubbles: true }));
    setTimeout(function () { f.blur(); }, 0);  // the keys stay the lecture's, not the field's
  }
  function seek(i) {
    index = Math.max(0, Math.min(stops.length - 1, i));
    var f = field();
    if (!f) { paced = false; shown = -1; show(index); return; }
    playAt(f, stops[index].at);
    show(index);
  }
  function follow() {
    var f = field();
    if (!f) return;
    var t = parseFloat(f.value);
    if (!isFinite(t)) return;
    var i = 0;
    while (i + 1 < stops.length && stops[i + 1].at <= t + 0.05) i++;
    index = i;
    show(i);
  }
  var NEXT = { PageDown: 1, ArrowRight: 1, ArrowDown: 1, PageUp: -1, ArrowLeft: -1, ArrowUp: -1 };
  window.addEventListener('keydown', function (e) {
    if (e.target && e.target.dataset && e.target.dataset.apf === 'cell') return;  // a cell being typed
    if ((e.key === 'r' || e.key === 'R') && stops[index].question) {
      e.preventDefault();
      e.stopImmediatePropagation();
      reveal();
      return;
    }
    if (!(e.key in NEXT)) return;  // the page has no other field to type in but the player's time
    e.preventDefault();
    e.stopImmediatePropagation();
    seek(index + NEXT[e.key]);
  }, true);
  var tries = 0;
  var start = setInterval(function () {
    tries++;
    if (field() || tries > 100) {
      clearInterval(start);
      seek(0);
      setInterval(follow, 200);
    }
  }, 100);
  show(0);
})();
"""


def _question(q: PageQuestion | None) -> dict | None:
    """A question as the page's script takes it, every word escaped for the caption's HTML."""
    if q is None:
        return None
    esc = html.escape
    choices = [[esc(v), esc(w)] for v, w in q.choices] if q.choices is not None else None
    return {
        "text": esc(q.text),
        "choices": choices,
        "right": [esc(r) for r in q.right],
        "answer": esc(q.answer),
        "reveal_at": q.reveal_at,
        "revealed_status": symbol_html(q.revealed_status),
    }


def paced_page(page: str, title: str, stops: list[PageStop], stop_seconds: float) -> str:
    """viser's exported ``page`` with the lecture's caption and keys added."""
    data = {
        "title": title,
        "stopSeconds": stop_seconds,
        "unpaced": "This page cannot go stop to stop with this viser: it plays each stop for "
        f"{stop_seconds:g} s (Space pauses).",
        "stops": [
            {
                **asdict(s),
                **{k: symbol_html(getattr(s, k)) for k in ("where", "title", "say", "status")},
                "question": _question(s.question),
            }
            for s in stops
        ],
    }
    payload = json.dumps(data).replace("</", "<\\/")  # no text of a lecture ends the script early
    script = _SCRIPT % {"field": PLAYER_TIME_FIELD_JS}
    added = (
        f"<style>{_STYLE}</style>"
        f'<div id="apf-caption" role="region" aria-label="{html.escape(title)}"></div>'
        f'<script type="application/json" id="apf-stops">{payload}</script>'
        f"<script>{script}</script>"
    )
    end = page.rindex("</body>")
    return page[:end] + added + page[end:]
