"""For a local cluster only: its workers' logs go to the farm command's own terminal, where
Dask's "Compute Failed" record of a failed task (the exception's repr and a traceback of our
own code) would print the error the command reports, cleanly, a moment later. A cluster's
own workers keep their logs whole: there, the record is the host's only copy."""

import logging

from distributed import WorkerPlugin

from .jobs import TASK_KEY_PREFIX


class _TaskFailures(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        message = str(record.msg)
        if not message.startswith("Compute Failed") or not record.args:
            return True
        return not str(record.args[0]).startswith(TASK_KEY_PREFIX)  # args[0]: the task's key


class QuietTaskFailures(WorkerPlugin):
    """Registered by the client on a local cluster; kept by workers a nanny restarts."""

    idempotent = True

    def setup(self, worker) -> None:
        logger = logging.getLogger("distributed.worker")
        if not any(isinstance(f, _TaskFailures) for f in logger.filters):
            logger.addFilter(_TaskFailures())
