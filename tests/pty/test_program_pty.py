"""A program played in the real ``dhsim`` in a pseudo-terminal: the program
panel, playback at ×4 to its end, the plot, and back (issue 19)."""

from __future__ import annotations

from pty_screen import PtyScreen


def test_the_demo_plays_to_its_end_in_a_real_terminal():
    with PtyScreen(["puma560"], size=(100, 30)) as screen:
        screen.wait_for("Th6")
        screen.send("g")
        screen.wait_for("Program demo")
        screen.send("]", "]")  # ×4: the 7.85 s demo in about 2 s
        screen.wait_for("×4")
        screen.send(" ")
        screen.wait_for("playing demo")
        screen.wait_for("played demo")  # however long the machine takes to play it
        # the panel's time, drawn with that status (the frame may arrive in two reads)
        screen.wait_for("7.85 / 7.85 s")
        screen.send("t")
        screen.wait_for("tool speed")
        screen.send("\x1b")
        screen.wait_for(lambda text: "tool speed" not in text and "Program demo" in text)
