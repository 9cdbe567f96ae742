"""Output files: paths refused before any computation, files written whole, interrupts
that leave only complete files, and repeated or ignored options refused."""

import os
import pathlib

import pytest

from thermocontact.cli import main
from thermocontact.io.files import atomic_write

CONTACT = ["contact", "--cylinder", "steel", "--half-plane", "cast-iron", "--radius", "450mm",
           "--load", "200kN/m", "--speed", "72km/h", "--friction", "0.35", "--lam", "-1"]


def _error(capsys, args):
    """Run the command; it must exit 2 with one line on standard error."""
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0]
    return err[0]


@pytest.fixture
def no_solve(monkeypatch):
    """Any attempt to compute fails the test: paths must be refused before."""
    import thermocontact.studies.physical_contact as pc

    def boom(*a, **k):
        raise AssertionError("computed before the output path was checked")
    monkeypatch.setattr(pc, "contact", boom)


@pytest.mark.parametrize("option", ["--csv", "--plot"])
def test_bad_output_paths_refused_before_computing(tmp_path, capsys, no_solve, option):
    afile = tmp_path / "a.png"
    afile.write_text("x")
    readonly = tmp_path / "ro"
    readonly.mkdir()
    readonly.chmod(0o500)
    bad = {
        "folder": str(tmp_path),
        "under a file": str(afile / "x.png"),
        "missing folder": str(tmp_path / "missing" / "x.png"),
        "too long": str(tmp_path / ("x" * 300 + ".png")),
        "empty": "",
    }
    if os.geteuid() != 0:  # root may write anywhere
        bad["read-only folder"] = str(readonly / "x.png")
    for what, path in bad.items():
        msg = _error(capsys, CONTACT + [option, path])
        assert msg.startswith(f"error: {option} must"), (what, msg)


def _lying_access(folder):
    """Whether ``os.access`` says ``folder`` is writable while nothing can be created in
    it (as root in /proc and /sys): only then can the probe be tested there."""
    import tempfile

    if not (os.path.isdir(folder) and os.access(folder, os.W_OK | os.X_OK)):
        return False
    try:
        fd, tmp = tempfile.mkstemp(dir=folder)
    except OSError:
        return True
    os.close(fd)
    os.unlink(tmp)
    return False


@pytest.mark.parametrize("option,path", [("--csv", "/proc/x.csv"), ("--plot", "/sys/x.png")])
def test_unwritable_places_refused_even_where_access_says_yes(capsys, no_solve, option, path):
    if not _lying_access(os.path.dirname(path)):
        pytest.skip("os.access does not claim this folder is writable here")
    msg = _error(capsys, CONTACT + [option, path])
    assert msg.startswith(f"error: {option} must be in a writable folder"), msg


def test_probe_refuses_where_nothing_can_be_created(tmp_path, monkeypatch):
    """Whatever os.access says, a folder where no file can be created is refused."""
    import tempfile

    from thermocontact.io.files import check_output_dir, check_output_file
    from thermocontact.problem.validation import InputError

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")
    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    with pytest.raises(InputError, match="--csv must be in a writable folder.*Permission"):
        check_output_file("--csv", str(tmp_path / "x.csv"))
    with pytest.raises(InputError, match="--out must be in a writable folder.*Permission"):
        check_output_dir("--out", str(tmp_path / "m.zarr"))


def test_failed_write_is_one_line_error(tmp_path):
    """An OSError while writing (here a folder where the file goes) is a one-line
    error naming the file, and leaves nothing behind."""
    from thermocontact.io.files import WriteError
    from thermocontact.problem.validation import InputError

    (tmp_path / "x.csv").mkdir()
    with pytest.raises(WriteError, match=r"could not write .*x\.csv \(") as info:
        with atomic_write(tmp_path / "x.csv") as fh:
            fh.write("a")
    assert isinstance(info.value, InputError) and "\n" not in str(info.value)
    assert sorted(os.listdir(tmp_path)) == ["x.csv"]


def test_plot_needs_a_picture_extension_and_csv_plot_differ(tmp_path, capsys, no_solve):
    assert "must end in one of .png" in _error(capsys, CONTACT + ["--plot", str(tmp_path / "x")])
    same = str(tmp_path / "x.png")
    assert "must be different files" in _error(capsys, CONTACT + ["--csv", same, "--plot", same])


def test_reproduce_out_refused(tmp_path, capsys):
    afile = tmp_path / "f"
    afile.write_text("x")
    for path in ("", str(afile), str(afile / "sub"), str(tmp_path / "a" / "b")):
        assert "--out must" in _error(capsys, ["reproduce", "--out", path, "--only", "fig5"])


def test_repeated_options_and_unknown_figures_refused(capsys):
    msg = _error(capsys, ["solve", "--pe", "5", "--fhpe", "0.2", "--K2-over-K1", "10",
                          "--lam", "-1", "--lam", "1"])
    assert "--lam must be given at most once" in msg
    assert "got 'bogus'" in _error(capsys, ["reproduce", "--only", "fig2", "--only", "bogus"])


def test_materials_file_read_even_with_inline_materials(tmp_path, capsys):
    inline = "E=210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5"
    args = ["contact", "--cylinder", inline, "--half-plane", inline, "--radius", "10mm",
            "--load", "1e4", "--speed", "1", "--friction", "0.1", "--lam", "-1"]
    assert "not found" in _error(capsys, args + ["--materials", str(tmp_path / "none.toml")])
    broken = tmp_path / "broken.toml"
    broken.write_text("[x\n")
    assert "invalid TOML" in _error(capsys, args + ["--materials", str(broken)])


def test_atomic_write_leaves_old_file_on_interrupt(tmp_path):
    path = tmp_path / "table.csv"
    path.write_text("complete old content\n")
    with pytest.raises(KeyboardInterrupt):
        with atomic_write(path) as fh:
            fh.write("half of the new")
            raise KeyboardInterrupt
    assert path.read_text() == "complete old content\n"
    assert os.listdir(tmp_path) == ["table.csv"]  # no temporary file left
    with atomic_write(path) as fh:
        fh.write("new\n")
    assert path.read_text() == "new\n"


def test_interrupted_reproduce_leaves_complete_files_and_counts_them(tmp_path, capsys,
                                                                     monkeypatch):
    """Interrupted while saving the second picture of fig5: the CSV and PNG written
    before are complete and counted, the SVG is absent (not truncated)."""
    import thermocontact.plotting.curves as curves

    real = curves.save_figure
    calls = []

    def interrupted(fig, path, written=None):
        calls.append(path)
        if len(calls) == 2:
            raise KeyboardInterrupt
        real(fig, path, written)
    monkeypatch.setattr(curves, "save_figure", interrupted)
    assert main(["reproduce", "--out", str(tmp_path), "--only", "fig5"]) == 130
    err = capsys.readouterr().err
    assert "interrupted: 2 complete files" in err
    assert sorted(os.listdir(tmp_path)) == ["fig5.csv", "fig5.png"]
    assert (tmp_path / "fig5.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "fig5.csv").read_text().rstrip().count("\n") > 10


#: The first lines of the drivers that are interrupted below: a command started from a
#: terminal takes Ctrl-C, whatever the test runner's own disposition of SIGINT (a process
#: started in the background of a shell ignores it, and its children inherit that; a
#: thread's blocked signals are inherited too).
INTERRUPTIBLE = ("import signal\n"
                 "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
                 "signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})\n")


def test_interrupt_while_importing_prints_no_traceback():
    """SIGINT while NumPy loads, while SciPy loads, or in the first solve ends the
    command with status 130 and one line, never a traceback.  The signal is sent at
    each of these known points (an import hook, or the solve, says so and waits), not
    after a delay."""
    import signal
    import subprocess
    import sys

    driver = INTERRUPTIBLE + (
        "import os, sys, time\n"
        "point = sys.argv.pop(1)\n"
        "def wait():\n"
        "    os.write(1, b'here\\n')\n"
        "    time.sleep(600)\n"
        "class Announce:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == point:\n"
        "            wait()\n"
        "if point == 'solve':\n"
        "    import thermocontact.api as api\n"
        "    api.solve = lambda *args, **kwargs: wait()\n"
        "else:\n"
        "    sys.meta_path.insert(0, Announce())\n"
        "from thermocontact.__main__ import main\n"
        "sys.exit(main(sys.argv[1:]))\n")
    for point in ("numpy", "scipy", "solve"):
        proc = subprocess.Popen([sys.executable, "-c", driver, point, "solve", "--pe", "5",
                                 "--fhpe", "0.2", "--K2-over-K1", "10", "--lam", "-1"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            assert proc.stdout.readline() == "here\n", point
            proc.send_signal(signal.SIGINT)
            _, err = proc.communicate(timeout=120)
        finally:
            if proc.poll() is None:
                proc.kill()
        assert proc.returncode == 130 and "Traceback" not in err, (point, err)
        assert len(err.strip().splitlines()) == 1, (point, err)


def test_picture_drawn_beside_equals_picture_drawn_here(tmp_path, capsys, monkeypatch):
    """`contact --plot` draws in a second process that imported Matplotlib while the
    contact was solved; the picture is the one drawn in this process, byte for byte."""
    import thermocontact.execution.executors as ex

    args = ["contact", "--cylinder", "copper", "--half-plane", "steel", "--radius", "50mm",
            "--load", "5kN/m", "--speed", "10", "--friction", "0.3", "--lam", "0"]
    assert main(args + ["--plot", str(tmp_path / "beside.png")]) == 0
    monkeypatch.setattr(ex, "cpu_count", lambda: 1)
    assert ex.side_process("math") is None
    assert main(args + ["--plot", str(tmp_path / "here.png")]) == 0
    capsys.readouterr()
    assert (tmp_path / "beside.png").read_bytes() == (tmp_path / "here.png").read_bytes()


def test_interrupted_contact_picture_leaves_no_process(tmp_path):
    """SIGINT while `contact --plot` solves (its picture process importing Matplotlib):
    status 130, one line, and no process of its group left behind.  The signal is sent
    at a known point, not after a delay: the solve is replaced by one that says so and
    waits."""
    import signal
    import subprocess
    import sys
    import time

    driver = INTERRUPTIBLE + (
        "import os, sys, time\n"
        "import thermocontact.api as api\n"
        "def solving(*args, **kwargs):\n"
        "    os.write(1, b'solving\\n')\n"
        "    time.sleep(600)\n"
        "api.contact = solving\n"
        "from thermocontact.__main__ import main\n"
        "sys.exit(main(sys.argv[1:]))\n")
    proc = subprocess.Popen([sys.executable, "-c", driver] + CONTACT
                            + ["--plot", str(tmp_path / "c.png")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        assert proc.stdout.readline() == "solving\n"
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130 and len(err.strip().splitlines()) == 1, err
    # The group's last process gone: polled, each look a tenth of a second apart.
    for _ in range(600):
        try:
            os.killpg(proc.pid, 0)
        except ProcessLookupError:
            break
        time.sleep(0.1)
    else:
        raise AssertionError("a process of the interrupted command is still running")


def test_interrupt_while_workers_start_is_no_traceback_of_theirs():
    """Ctrl-C sent to the whole process group while a picture process or pool workers
    start (before their initialiser runs) is held in the children until they are ready,
    then dropped there: the parent alone is interrupted, and nothing of the children's
    start-up is printed.  The signal is sent inside the window, at a known point."""
    import subprocess
    import sys

    driver = INTERRUPTIBLE + (
        "import os, signal, sys\n"
        "from thermocontact.execution import executors as ex\n"
        "import concurrent.futures as cf, multiprocessing\n"
        "kind = sys.argv[1]\n"
        "if kind == 'side':\n"
        "    pool = cf.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context('fork'),\n"
        "                                  initializer=ex._import_quietly, initargs=(['math'],))\n"
        "else:\n"
        "    pool = cf.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context('fork'),\n"
        "                                  initializer=ex._single_thread)\n"
        "def start_and_interrupt():\n"
        "    futures = [pool.submit(abs, -1)]\n"
        "    os.killpg(0, signal.SIGINT)\n"
        "    return futures\n"
        "try:\n"
        "    futures = ex._interrupts_held(start_and_interrupt)\n"
        "    sys.stdout.write('not interrupted\\n')\n"
        "except KeyboardInterrupt:\n"
        "    sys.stdout.write('interrupted\\n')\n"
        "    sys.stdout.write(str(pool.submit(abs, -2).result()) + '\\n')\n"
        "pool.shutdown()\n")
    for kind in ("side", "pool"):
        proc = subprocess.run([sys.executable, "-c", driver, kind], capture_output=True,
                              text=True, timeout=120, start_new_session=True)
        # The parent interrupted once, its children alive and working, nothing printed.
        assert proc.returncode == 0 and proc.stdout == "interrupted\n2\n", (kind, proc)
        assert proc.stderr == "", (kind, proc.stderr)


def test_no_noise_after_refusal_or_with_no_branch(tmp_path, capsys):
    """A load of 1e-300 N/m is refused in one line (no RuntimeWarning on the way), and a
    picture of a contact with no branch is drawn without a warning (no empty legend)."""
    import warnings

    from thermocontact.plotting.curves import contact_figure
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalContact, PhysicalProblem

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        args = CONTACT[:7] + ["--load", "1e-300 N/m"] + CONTACT[9:]
        msg = _error(capsys, args)
        assert "load 1e-300 N/m" in msg
        prob = PhysicalProblem(get_material("steel"), get_material("cast-iron"), 0.45, 2e5,
                               20.0, 0.35, 0.5)
        contact_figure(PhysicalContact(prob, (), None, "none", None), str(tmp_path / "c.png"))
    assert (tmp_path / "c.png").stat().st_size > 1000


def test_special_files_refused_and_links_written_through(tmp_path, capsys, no_solve):
    """A FIFO or a device where the file goes is refused in one line (the file renamed
    over it would replace it: /dev/null made a regular file), before any work and by the
    writer itself; a symbolic link stays a link, the file it names is written."""
    import stat

    from thermocontact.io.files import WriteError, check_output_file
    from thermocontact.problem.validation import InputError

    fifo = tmp_path / "f.csv"
    os.mkfifo(fifo)
    for option, path in (("--csv", str(fifo)), ("--csv", os.devnull), ("--plot", os.devnull)):
        msg = _error(capsys, CONTACT + [option, path])
        assert msg.startswith(f"error: {option} must be a regular file, got {path!r} (a "), msg
    with pytest.raises(WriteError, match=r"could not write .*f\.csv \(it is a FIFO, not a file\)"):
        with atomic_write(fifo) as fh:
            fh.write("a")
    assert stat.S_ISFIFO(os.stat(fifo).st_mode) and stat.S_ISCHR(os.stat(os.devnull).st_mode)

    target = tmp_path / "data" / "t.csv"
    target.parent.mkdir()
    target.write_text("old")
    link = tmp_path / "l.csv"
    link.symlink_to(target)
    assert check_output_file("--csv", str(link)) == str(link)
    with atomic_write(link) as fh:
        fh.write("new")
    assert link.is_symlink() and target.read_text() == "new"
    assert sorted(os.listdir(target.parent)) == ["t.csv"]
    # A relative link too; a loop of links is refused.
    rel = tmp_path / "data" / "r.csv"
    rel.symlink_to("t.csv")
    with atomic_write(rel) as fh:
        fh.write("again")
    assert rel.is_symlink() and target.read_text() == "again"
    loop = tmp_path / "loop.csv"
    loop.symlink_to(loop)
    with pytest.raises(InputError, match="--csv must not be a loop of symbolic links"):
        check_output_file("--csv", str(loop))


def test_a_folder_written_over_a_link_leaves_the_tree_it_names(tmp_path):
    """A Zarr store's folder is written where it is: a link to a folder is not followed,
    and the tree it names is not removed."""
    from thermocontact.io.files import WriteError, atomic_path

    tree = tmp_path / "kept"
    tree.mkdir()
    (tree / "a.txt").write_text("x")
    link = tmp_path / "m.zarr"
    link.symlink_to(tree)
    try:
        with atomic_path(link, folder=True) as tmp:
            (pathlib.Path(tmp) / "b.txt").write_text("y")
    except WriteError:
        pass  # refused: the link is not a folder to replace
    assert (tree / "a.txt").read_text() == "x"
