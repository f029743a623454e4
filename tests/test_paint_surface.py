"""The paint surface is a plane as wide as the canvas: what it costs each frame is what the canvas
costs (docs/PERFORMANCE.md: with viser's lit default, 350-480 ms a frame in software GL)."""

from __future__ import annotations

from apf_viz.ui.scene.paint_surface import PLANE_SIDE, PaintSurface


class _Plane:
    def __init__(self) -> None:
        self.removed = False
        self.drag = None

    def on_drag(self, fn) -> None:
        self.drag = fn

    def remove(self) -> None:
        self.removed = True


class _Scene:
    def __init__(self) -> None:
        self.added: list[dict] = []
        self.planes: list[_Plane] = []

    def add_box(self, name: str, **kwargs) -> _Plane:
        self.added.append({"name": name, **kwargs})
        self.planes.append(_Plane())
        return self.planes[-1]


class _Client:
    def __init__(self) -> None:
        self.scene = _Scene()


def test_the_plane_is_invisible_unlit_and_shown_once_while_wanted():
    client = _Client()
    strokes: list[tuple] = []
    surface = PaintSurface(client, lambda c, phase, point: strokes.append((phase, point)))
    surface.show(True)
    surface.show(True)  # shown once, however often a refresh asks
    assert len(client.scene.added) == 1
    box = client.scene.added[0]
    assert box["opacity"] == 0.0 and box["material"] != "standard"  # no lit full-canvas pass
    assert box["dimensions"][0] == box["dimensions"][1] == PLANE_SIDE
    surface.show(False)
    assert client.scene.planes[0].removed
    surface.show(True)
    assert len(client.scene.added) == 2
