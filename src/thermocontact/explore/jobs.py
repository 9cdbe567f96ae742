"""Background jobs of the explorer: a map or a transient run, each in a process of its
own, with its progress, and cancelled by ending that process.

A job runs :func:`~thermocontact.explore.adapter.run_job` in a child process, so that
the page's single contacts (in the server's threads) keep their speed while it runs
and a cancel stops it at once.  At most ``running`` jobs compute at a time (one per
core); the others wait, said so by their status.  Identical requests share one job
(twenty sessions asking for the same map compute it once); a job is ended when every
session that asked for it has cancelled it.  Each job writes only in its own folder
under the server's temporary folder; the oldest finished jobs are forgotten, and
their folders removed, beyond ``kept``.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import threading
import time

from .adapter import UserError, job_context, run_job

__all__ = ["Jobs"]

#: Seconds between two looks at a running job's process.
POLL = 0.05


class Job:
    """One background computation: its kind, state, what identifies its result (key),
    folder, process, progress and status."""

    def __init__(self, kind, state, key, folder, ctx):
        self.id = secrets.token_urlsafe(12)
        self.kind, self.state, self.key, self.folder = kind, dict(state), key, folder
        self.progress = ctx.Array("d", 2, lock=False)
        self.process = None
        self.status = "queued"  # queued, running, done, failed, cancelled
        self.view = self.error = None
        self.holders = 1
        self.started = time.monotonic()
        self.seconds = None

    def report(self) -> dict:
        done, total = self.progress[0], self.progress[1]
        return {"id": self.id, "kind": self.kind, "status": self.status,
                "done": done, "total": total,
                "seconds": (time.monotonic() - self.started if self.seconds is None
                            else self.seconds),
                "view": self.view, "error": self.error}


class Jobs:
    """The server's background jobs.

    Parameters
    ----------
    folder : str
        The server's temporary folder: each job writes in a folder of its own there.
    running : int
        Jobs computing at once; the others wait.
    kept : int
        Jobs remembered (with their files); the oldest finished are forgotten first, and
        a job is refused while this many wait or compute.
    """

    def __init__(self, folder, running=2, kept=40):
        self.folder, self.kept = folder, kept
        # Started by a fork server that has imported the library once: a job starts in
        # a fraction of a second and never inherits the server's threads.
        self._ctx = job_context()
        self._slots = threading.Semaphore(running)
        self._lock = threading.Lock()
        self._jobs: dict[str, Job] = {}
        self._closed = False

    def start(self, kind, state, key) -> str:
        """A job computing ``kind`` (``"map"`` or ``"transient"``) for ``state``, or the
        one already computing the same ``key`` (what identifies the result); its id."""
        with self._lock:
            for job in self._jobs.values():
                if (job.kind, job.key) == (kind, key) and job.status in (
                        "queued", "running", "done"):
                    job.holders += 1
                    return job.id
            self._forget_old()
            waiting = sum(j.status in ("queued", "running") for j in self._jobs.values())
            if waiting >= self.kept:
                raise UserError(f"the server has {waiting} maps and runs to compute: cancel "
                                f"one, or wait for one to finish")
            folder = os.path.join(self.folder, f"job-{len(os.listdir(self.folder))}-"
                                               f"{secrets.token_hex(4)}")
            os.mkdir(folder)
            job = Job(kind, state, key, folder, self._ctx)
            self._jobs[job.id] = job
        threading.Thread(target=self._run, args=(job,), daemon=True,
                         name=f"explore-{kind}").start()
        return job.id

    def _run(self, job):
        with self._slots:
            with self._lock:
                if job.status != "queued" or self._closed:
                    return
                job.process = self._ctx.Process(
                    target=run_job, args=(job.kind, job.state, job.folder, job.progress),
                    daemon=True)
                job.process.start()
                job.status = "running"
                job.started = time.monotonic()  # its seconds count from here on
            job.process.join()
            with self._lock:
                job.seconds = time.monotonic() - job.started
                if job.status == "cancelled":
                    return
                for name, attr, status in (("view.json", "view", "done"),
                                           ("error.json", "error", "failed")):
                    path = os.path.join(job.folder, name)
                    if os.path.exists(path):
                        with open(path) as fh:
                            setattr(job, attr, json.load(fh))
                        job.status = status
                        break
                else:
                    job.status = "failed"
                    job.error = {"message": f"the {job.kind} stopped without an answer "
                                            f"(exit code {job.process.exitcode})",
                                 "fields": {}}

    def report(self, job_id) -> dict | None:
        """The job's status, progress and, once done, its view or error; None if unknown."""
        with self._lock:
            job = self._jobs.get(job_id)
            return None if job is None else job.report()

    def cancel(self, job_id) -> bool:
        """Drop one session's interest in the job; the last one ends its process."""
        with self._lock:
            job = self._jobs.get(job_id)
            if job is None:
                return False
            job.holders -= 1
            if job.holders > 0 or job.status not in ("queued", "running"):
                return True
            job.status = "cancelled"
            job.seconds = time.monotonic() - job.started
            process = job.process
        if process is not None and process.is_alive():
            process.terminate()
        return True

    def file(self, job_id, kind) -> str | None:
        """The NetCDF file of a finished job of ``kind``, or None: a path made here,
        never one a client gives."""
        with self._lock:
            job = self._jobs.get(job_id)
            if job is None or job.kind != kind or job.status != "done":
                return None
            path = os.path.join(job.folder, f"{kind}.nc")
        return path if os.path.exists(path) else None

    def _forget_old(self):
        """With the lock held: forget the oldest finished jobs beyond ``kept``."""
        finished = [j for j in self._jobs.values() if j.status in ("done", "failed",
                                                                   "cancelled")]
        for job in sorted(finished, key=lambda j: j.started)[:max(0, len(self._jobs)
                                                                   - self.kept + 1)]:
            del self._jobs[job.id]
            shutil.rmtree(job.folder, ignore_errors=True)

    def close(self):
        """End every job's process."""
        with self._lock:
            self._closed = True
            processes = [j.process for j in self._jobs.values() if j.process is not None]
        for process in processes:
            if process.is_alive():
                process.terminate()
            process.join(timeout=5)
