"""How the engine and the operators report Whitted's own failures (not the user's mistakes):
as an error report, which makes `blender -b` exit 1 and shows in Blender's UI, with the
traceback on the console for the bug report, never raised into Blender."""

import traceback


def report_internal_failure(reporter, action: str, error: Exception) -> None:
    """`reporter` is a RenderEngine or Operator (anything with report()); `action` is what
    failed ("render", "import")."""
    traceback.print_exc()
    kind = type(error).__name__
    reporter.report(
        {"ERROR"}, f"Whitted: the {action} failed: {kind}: {error} (traceback on the console)"
    )
