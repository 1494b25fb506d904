"""A timer in Blender's window that, when its step raises, says so and quits.

Blender prints a timer's traceback and drops the timer, and its window stays open: a test
driving the window would wait for its subprocess's timeout (300 s) and learn nothing. Here
the traceback goes to the test's output file (as {"error": ...}) and Blender's process ends
at once."""

import json
import os
import traceback

import bpy


def register_step(step, out_path: str, first_interval: float = 2.0) -> None:
    """Run step() as a timer (its return value is the next interval, or None to stop)."""

    def guarded():
        try:
            return step()
        except BaseException:
            with open(out_path, "w") as f:
                json.dump({"error": traceback.format_exc()}, f)
            traceback.print_exc()
            # Not wm.quit_blender: in a fresh-clone run under load a step raised and the quit
            # did not end Blender either (the test waited its 300 s with the window open)
            os._exit(1)

    bpy.app.timers.register(guarded, first_interval=first_interval)


# Blender refuses writes to its data from Python while any thread is inside a render
# engine's callback or a draw (a global flag), so a timer step that starts the next
# preview can meet a refusal while the last preview's render thread is still finishing
# (seen in a fresh-clone run under load): such a step is tried again at the next tick
REFUSED = ("can't modify blend data in this state", "is not allowed")


def written(action) -> bool:
    """Run action(); False if Blender refused its writes (try it at the next tick)."""
    try:
        action()
    except (RuntimeError, AttributeError) as error:
        if not any(words in str(error) for words in REFUSED):
            raise
        return False
    return True
