"""The `check` gate never passes what it has not proven: a reader that leaves early, report folders
checked before any work, unique report names, a scenario that checks nothing, `--quiet`, `--set`, and
the default time limit of a run."""

import subprocess
import sys

# a counter that counts to LIMIT; "never HALF" is violated after HALF steps, so its trace is long
LONG = """net C;
val LIMIT = 400;
colset N = int with 0..LIMIT;
var n : N;
place P : N = 1`0;
trans Inc [n < LIMIT];
arc P -> Inc : n;
arc Inc -> P : n + 1;
"""


def scenario(folder, name="s.toml", body="", model=LONG, head=""):
    """Write `c.cpnet` and a scenario naming it in `folder`; returns the scenario's path."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "c.cpnet").write_text(model, encoding="utf-8")
    path = folder / name
    path.write_text(head + 'model = "c.cpnet"\n' + body, encoding="utf-8")
    return str(path)


def prop(name, expr, kind="invariant"):
    return f'[[property]]\nname = "{name}"\nkind = "{kind}"\nexpr = "{expr}"\n'


# five violated invariants, each with a trace of 200 steps or more: far more than a pipe's buffer
VIOLATIONS = "".join(prop(f"never {k}", f"C'P 1 <> (1`{k})") for k in (200, 210, 220, 230, 240))


def cli(*args, cwd=None, stdout=subprocess.PIPE, stderr=subprocess.PIPE, close=()):
    """Run `cpn-verify` in a subprocess; the pipes named in `close` lose their reader at once."""
    p = subprocess.Popen([sys.executable, "-m", "cpn", *args], cwd=cwd, stdout=stdout, stderr=stderr,
                         stdin=subprocess.DEVNULL, text=True)
    for name in close:
        getattr(p, name).close()  # nobody reads it any more: every write to it fails with EPIPE
    out = p.stdout.read() if p.stdout and "stdout" not in close else ""
    err = p.stderr.read() if p.stderr and "stderr" not in close else ""
    p.wait(timeout=300)
    return p.returncode, out, err


# ---------------------------------------------------------------- a reader that goes away early


def test_a_closed_standard_output_keeps_the_verdict_of_check(tmp_path):
    spec = scenario(tmp_path, body=VIOLATIONS)
    code, _, err = cli("check", "--no-reports", spec, close=("stdout",))
    assert code == 1, err
    assert "Traceback" not in err and "BrokenPipe" not in err


def test_a_closed_standard_output_after_some_lines_keeps_the_verdict(tmp_path):
    spec = scenario(tmp_path, body=VIOLATIONS)
    p = subprocess.Popen([sys.executable, "-m", "cpn", "check", "--no-reports", spec], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True)
    first = [p.stdout.readline() for _ in range(3)]  # `| head -n 3`
    p.stdout.close()
    err = p.stderr.read()
    assert p.wait(timeout=300) == 1, err
    assert "violated" in first[0]


def test_a_closed_standard_error_keeps_the_status_of_a_bad_model(tmp_path):
    bad = tmp_path / "bad.cpnet"
    bad.write_text("colset C = int;\nplace P : D;\n" * 200, encoding="utf-8")
    for command in ("lint", "explore"):
        code, _, _ = cli(command, str(bad), close=("stderr",))
        assert code == 65, command


def test_a_closed_standard_output_keeps_the_status_of_explore_and_lint(tmp_path):
    model = tmp_path / "c.cpnet"
    model.write_text(LONG, encoding="utf-8")
    code, _, err = cli("explore", str(model), "--max-listed", "0", close=("stdout",))
    assert code == 0 and "Traceback" not in err
    code, _, err = cli("explore", str(model), "--max-states", "5", close=("stdout",))
    assert code == 2 and "Traceback" not in err
    code, _, err = cli("lint", str(model), close=("stdout",))
    assert code == 0 and "Traceback" not in err
