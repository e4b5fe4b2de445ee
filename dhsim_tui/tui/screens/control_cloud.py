"""The workspace cloud for the control screen (``W``): the points the tool can
reach, sampled once in a worker and shown faint behind the arm in every view.
"""

from __future__ import annotations

import numpy as np
from textual import work
from textual.worker import get_current_worker

from dhsim_tui.core.model.robot import Robot
from dhsim_tui.tui.screens.control_branches import SEARCH_ERRORS

#: how many points the workspace cloud (W) has
CLOUD_POINTS = 20000


class WorkspaceCloud:
    """Mixed into the control screen, which has ``robot``, ``_views``, ``say``,
    ``workers`` and the ``cloud_state`` and ``_cloud_points`` it sets up."""

    # -- W: the workspace cloud ----------------------------------------------------------
    def action_workspace(self) -> None:
        """Show the points the tool can reach, faint behind the arm in every
        view (sampled once, in a worker); again: hide them, or stop waiting."""
        if self.cloud_state != "off":
            self.cloud_state = "off"
            self.workers.cancel_group(self, "workspace")
            self._views.set_cloud(None)
            self.say("workspace cloud off")
            return
        self.cloud_state = "computing"
        if self._cloud_points is not None:
            self._cloud_ready(self._cloud_points)
            return
        self.say("sampling the workspace… (W again: never mind)")
        self._sample_workspace(self.robot)

    @work(thread=True, exclusive=True, group="workspace")
    def _sample_workspace(self, robot: Robot) -> None:
        from dhsim_tui.core.analysis.workspace import position_chunks

        worker = get_current_worker()
        chunks = []
        try:
            with np.errstate(all="ignore"):  # sample_positions, chunk by chunk: W may stop it
                for chunk in position_chunks(robot, CLOUD_POINTS, 0):
                    if worker.is_cancelled:
                        return
                    chunks.append(chunk)
            points = np.concatenate(chunks)
        except SEARCH_ERRORS as exc:
            if not worker.is_cancelled:
                self.app.call_from_thread(self._cloud_failed, str(exc))
            return
        if not worker.is_cancelled:  # W again, or the screen went away
            self.app.call_from_thread(self._cloud_ready, points)

    def _cloud_failed(self, reason: str) -> None:
        if self.cloud_state == "computing":
            self.cloud_state = "off"
            self.say(f"workspace not sampled: {reason}", error=True)

    def _cloud_ready(self, points) -> None:
        """The samples (kept: the joints, base and tool don't change on this
        screen); shown unless W was pressed again meanwhile."""
        self._cloud_points = points
        if self.cloud_state != "computing":
            return
        self.cloud_state = "on"
        self._views.set_cloud(points)
        self.say(f"workspace: {len(points)} positions the tool can reach (W hides them)")
