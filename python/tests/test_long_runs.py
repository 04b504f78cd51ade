# Long runs: Ctrl-C (SIGINT) stops erkn.solve cleanly with the output so far, progress(t) is
# called between chunks, and chunking changes nothing in the trajectory or the output.
import ctypes
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import erkn

# A solve that takes minutes unless interrupted (built-in potential: the GIL is released while
# stepping, so only the checks between chunks can see the signal).
LONG_SOLVE = textwrap.dedent("""
    import sys, numpy as np, erkn
    grad = {grad}
    print("started", flush=True)
    try:
        erkn.solve(4.0, grad, q0={q0}, p0=np.array([0.1, 0.2]), t_span=(0, 1e9), h=0.01,
                   {output}, method="{method}")
    except KeyboardInterrupt as e:
        sol = e.solution
        ok = sol.t.size >= 1 and np.all(np.isfinite(sol.q)) and sol.t[-1] < 1e9
        print("interrupted", sol.t.size, sol.t[-1], ok, flush=True)
        sys.exit(0 if ok else 3)
    sys.exit(4)
""")


def method():
    return next(m["name"] for m in erkn.methods() if m["kind"] == "explicit")


def interrupted(proc, after):
    """Sends SIGINT `after` seconds into the run; (stdout, seconds from SIGINT to exit). The
    child is killed if it does not stop (a failing test leaves no 1e9-step run behind)."""
    try:
        assert proc.stdout.readline().strip() == "started"
        time.sleep(after)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        out, _ = proc.communicate(timeout=60)
        return out, time.monotonic() - sent
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


# With output times the last state joins those reached (t_eval's second time, 1e8, is far beyond
# the interrupted run: without it the output would end at t = 0).
BUILTIN, EVERY = 'erkn.potential("phi4")', "every=10**6"
LIST, ARRAY = "[0.5, -0.3]", "np.array([0.5, -0.3])"


# (A name with float64 arrays: solve's common call, in its C++ entry.)
@pytest.mark.parametrize("grad, q0, output", [
    (BUILTIN, LIST, EVERY), ("lambda q: q**3", LIST, EVERY),
    (BUILTIN, LIST, "t_eval=np.linspace(0, 1e9, 11)"), ('"phi4"', ARRAY, EVERY)],
    ids=["builtin", "python", "t_eval", "common call"])
def test_sigint_stops_a_long_solve_and_keeps_the_output(grad, q0, output):
    code = LONG_SOLVE.format(grad=grad, q0=q0, method=method(), output=output)
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                            env=dict(os.environ))
    out, latency = interrupted(proc, after=1.5)  # (well into the run, past several chunks)
    assert proc.returncode == 0, out
    fields = out.split()
    assert fields[0] == "interrupted" and fields[-1] == "True", out
    assert float(fields[2]) > 0  # steps were taken and the last state kept
    assert latency < 5, f"the run stopped {latency:.1f} s after SIGINT"


def test_negative_control_without_sigint_the_long_solve_keeps_running():
    code = LONG_SOLVE.format(grad=BUILTIN, q0=LIST, method=method(), output=EVERY)
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "started"
        with pytest.raises(subprocess.TimeoutExpired):
            proc.wait(timeout=2)
    finally:
        proc.kill()
        proc.wait()


def test_progress_is_called_with_increasing_times_ending_at_t1():
    seen = []
    kw = dict(q0=[0.5, -0.3], p0=[0.1, 0.2], t_span=(0, 2000.0), h=0.01, every=1000)
    sol = erkn.solve(4.0, "phi4", progress=seen.append, **kw)
    assert len(seen) >= 3 and seen[-1] == 2000.0
    assert all(a < b for a, b in zip(seen, seen[1:]))
    # chunking leaves the trajectory and the output as one call makes them
    run = erkn.Integrator(4.0, "phi4", q0=kw["q0"], p0=kw["p0"], h=0.01)
    run.integrate(2000.0)
    assert np.array_equal(run.q, sol.q[-1])
    plain = erkn.solve(4.0, "phi4", progress=False, **kw)
    assert np.array_equal(plain.q, sol.q) and np.array_equal(plain.t, sol.t)
    t_eval = np.linspace(0, 2000.0, 77)
    a = erkn.solve(4.0, "phi4", t_eval=t_eval, progress=lambda t: None, **kw)
    assert np.array_equal(a.t, t_eval) and np.abs(a.q[-1] - sol.q[-1]).max() == 0


def test_an_exception_from_progress_stops_the_run_with_its_output():
    def progress(t):
        if t > 100:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough") as info:
        erkn.solve(4.0, "phi4", q0=[0.5, -0.3], p0=[0.1, 0.2], t_span=(0, 2000.0), h=0.01,
                   every=100, progress=progress)
    assert 100 < info.value.solution.t[-1] < 2000


def test_progress_true_draws_a_bar_and_bad_progress_is_refused(capsys):
    erkn.solve(4.0, "phi4", q0=[0.5], p0=[0.1], t_span=(0, 10.0), h=0.01, progress=True)
    assert "100.0 %" in capsys.readouterr().err
    erkn.solve(4.0, "phi4", q0=[0.5], p0=[0.1], t_span=(0, 10.0), h=0.01)
    assert capsys.readouterr().err == ""  # (not a terminal: no bar by default)
    with pytest.raises(erkn.Error, match="progress must be"):
        erkn.solve(4.0, "phi4", q0=[0.5], p0=[0.1], t_span=(0, 1.0), h=0.01, progress="yes")


@pytest.mark.parametrize("every", [1, 3, 4096, 5000, 10**6])
def test_chunked_output_every_k_steps_is_that_of_one_call(every):
    # (chunks of 4096, 8192, ... steps: `every` dividing them, not dividing them, and larger)
    kw = dict(q0=[0.5, -0.3], p0=[0.1, 0.2], h=0.01)
    steps = 60000 if every > 1 else 9000
    sol = erkn.solve(4.0, "phi4", t_span=(0, steps * 0.01), every=every, progress=lambda t: None,
                     **kw)
    seen = []
    run = erkn.Integrator(4.0, "phi4", **kw)
    run.integrate(steps * 0.01, observer=lambda t, q, p: seen.append((t, q)), every=every)
    assert np.array_equal(sol.t[1:], [t for t, _ in seen])
    assert np.array_equal(sol.q[1:], np.array([q for _, q in seen]))
    assert len(sol.t) == 1 + steps // every + (steps % every != 0)


LONG_INTEGRATOR = textwrap.dedent("""
    import sys, numpy as np, erkn
    run = erkn.Integrator(4.0, "phi4", q0=[0.5, -0.3], p0=[0.1, 0.2], h=0.01, method="{method}")
    print("started", flush=True)
    try:
        {call}
    except KeyboardInterrupt:
        ok = 0 < run.t < 1e9 and np.all(np.isfinite(run.q))
        print("interrupted", run.t, ok, flush=True)
        sys.exit(0 if ok else 3)
    sys.exit(4)
""")


@pytest.mark.parametrize("call", ["run.integrate(1e9)", "run.step(10**11)"])
def test_sigint_stops_integrator_calls_without_output_at_their_last_step(call):
    code = LONG_INTEGRATOR.format(method=method(), call=call)
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    out, _ = interrupted(proc, after=1.0)
    assert proc.returncode == 0 and out.split()[-1] == "True", out


def test_chunked_step_and_integrate_are_one_call():
    kw = dict(q0=[0.5, -0.3], p0=[0.1, 0.2], h=0.01)
    a, b, c = (erkn.Integrator(4.0, "phi4", **kw) for _ in range(3))
    a.step(50000)  # (chunks of 4096, 8192, ... steps)
    b.integrate(500.0)
    for _ in range(50000):
        c.step()
    assert np.array_equal(a.q, c.q) and np.array_equal(b.q, c.q) and a.t == b.t == c.t
    assert a.statistics["steps"] == 50000


def test_a_long_solve_with_a_builtin_potential_steps_without_the_gil(longest_stall):
    # (Short runs keep it: below some microseconds of work releasing it costs more than it frees.)
    def solve(t_end):
        return lambda: erkn.solve(4.0, "sine", q0=np.full(8, 0.1), p0=np.zeros(8),
                                  t_span=(0, t_end), h=0.01, method=method(), every=10**9)
    t_end, alone = 1.0, 0.0
    while alone < 0.1:  # a run long enough to see a stall
        t_end *= 2
        gap, alone = longest_stall(solve(t_end))
    assert gap < 0.5 * alone, (gap, alone)


def test_negative_control_a_call_holding_the_gil_stalls_this_thread(longest_stall):
    libc = ctypes.PyDLL(None)  # (a PyDLL's calls keep the GIL, a CDLL's release it)
    gap, alone = longest_stall(lambda: libc.usleep(200000))
    assert gap > 0.5 * alone, (gap, alone)
    gap, alone = longest_stall(lambda: ctypes.CDLL(None).usleep(200000))
    assert gap < 0.5 * alone, (gap, alone)
