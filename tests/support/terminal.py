"""Child processes that take Ctrl-C as they would from a terminal."""

import signal


def ctrl_c_as_in_a_terminal() -> None:
    """A `preexec_fn`: SIGINT back to its default before the child starts. A job a
    non-interactive shell starts with `&` (as `make test` starts its second lane) ignores
    SIGINT, the child inherits that, and Python then installs no Ctrl-C handler: the tests
    of Ctrl-C would test nothing there."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
