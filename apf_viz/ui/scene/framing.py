"""Framing the browsers' cameras on the run."""

from __future__ import annotations

from apf_viz.ui.scene.camera import _unskipped, camera_aspect, pose_for
from apf_viz.ui.scene.canvas import Canvas
from apf_viz.ui.scene.style import NARROW_ASPECT, Bounds


class Framing(Canvas):
    """Frames browsers' cameras on the run."""

    def camera_pose(
        self,
        aspect: float = NARROW_ASPECT,
        caption_room: float = 0.0,
        bounds: Bounds | None = None,
    ) -> tuple[tuple[float, float, float], tuple[float, float, float], float]:
        """:func:`pose_for` the run's box, or ``bounds`` (one with room to grow, :func:`grown_box`)."""
        return pose_for(self.bounds if bounds is None else bounds, aspect, caption_room)

    def frame_initial_camera(
        self,
        initial,
        bounds: Bounds | None = None,
        aspect: float = NARROW_ASPECT,
        caption_room: float = 0.0,
    ) -> None:
        """The pose new browsers start from (and "Reset View" returns to): the run, or ``bounds``, on a
        canvas of ``aspect`` with ``caption_room`` left free at the bottom (:meth:`camera_pose`)."""
        position, look_at, fov = self.framed_pose = self.camera_pose(aspect, caption_room, bounds)
        initial.fov = fov
        initial.up = (0.0, 0.0, 1.0)
        initial.position = position
        initial.look_at = look_at

    def frame_camera(
        self, camera, caption_room: float = 0.0, bounds: Bounds | None = None
    ) -> tuple[tuple[float, float, float] | None, float]:
        """Move a connected browser's camera to the whole run, or to ``bounds`` (position first: it drags
        look_at along), fitted to that browser's canvas (``caption_room``: :meth:`camera_pose`). Returns the
        position sent (None if none could be) and the aspect it was fitted to."""
        aspect = camera_aspect(camera)
        position, look_at, fov = self.camera_pose(aspect, caption_room, bounds)
        try:
            camera.fov = _unskipped(camera.fov, fov)
            camera.position = _unskipped(camera.position, position)
            camera.look_at = _unskipped(camera.look_at, look_at)
        except AssertionError:
            return None, aspect  # the browser has not reported its camera yet; its initial pose is right
        return position, aspect
