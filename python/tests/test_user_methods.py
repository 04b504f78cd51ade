# A user's explicit methods as data: erkn-generate --json, then erkn.load_methods. Each check runs
# in a fresh interpreter, so the loaded methods stay out of the other tests' registry.
import os
import re
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

pytestmark = pytest.mark.skipif("ERKN_GENERATE" not in os.environ,
                                reason="erkn-generate's path is not given (no generator)")


def explicit_blocks():
    """erkn's own explicit methods with plain kicks and no processor, from generator/methods.spec,
    renamed (--json refuses processed methods: the runtime has no processor yet)."""
    text = (SOURCE_DIR / "generator" / "methods.spec").read_text()
    blocks = re.findall(r"^method .*?(?=^method |\Z)", text, re.S | re.M)
    out = []
    for b in blocks:
        if re.search(r"^kind\s+explicit", b, re.M) and not re.search(r"^(modified|pre_)", b, re.M):
            name = re.match(r"method\s+(\S+)", b).group(1)
            b = re.sub(r"^rkn .*\n", "", b, flags=re.M)
            out.append((name, re.sub(r"^method\s+\S+", f"method    {name}_json", b, count=1)))
    return out


@pytest.fixture(scope="module")
def methods_json(tmp_path_factory):
    work = tmp_path_factory.mktemp("json")
    blocks = explicit_blocks()
    (work / "methods.spec").write_text("".join(b for _, b in blocks))
    subprocess.run([os.environ["ERKN_GENERATE"], str(work / "methods.spec"), "--out",
                    str(work / "out"), "--json"], check=True, capture_output=True)
    return [name for name, _ in blocks], work / "out" / "methods.json"


def run(code, *args):
    return subprocess.run([sys.executable, "-c", code, *map(str, args)], capture_output=True,
                          text=True)


SOLVE_BOTH = """
import sys, erkn, numpy as np
loaded = erkn.load_methods(sys.argv[1])
M = erkn.circulant(np.array([2.0, -1.0] + [0.0] * 12 + [-1.0]) * 4)
q0, p0 = np.linspace(0, 1, 15), np.cos(np.arange(15.0))
for m in loaded:
    own = m["name"][:-len("_json")]
    a, b = (erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 3), h=0.05, method=x)
            for x in (own, m["name"]))
    assert m["order"] == next(x for x in erkn.methods() if x["name"] == own)["order"], own
    assert np.array_equal(a.q, b.q) and np.array_equal(a.p, b.p), own
print(len(loaded))
"""


def test_loaded_methods_integrate_bit_identically_to_the_compiled_ones(methods_json):
    names, path = methods_json
    r = run(SOLVE_BOTH, path)
    assert r.returncode == 0, r.stderr
    assert int(r.stdout) == len(names) >= 11


LOAD = """
import sys, erkn
before = len(erkn.methods())
try:
    erkn.load_methods(sys.argv[1])
except erkn.Error as e:
    assert len(erkn.methods()) == before
    print("refused:", e)
else:
    print("loaded")
"""


def test_a_changed_digit_is_refused_naming_the_condition(methods_json, tmp_path):
    _, path = methods_json
    text = path.read_text()
    # d_1 of Yoshida4_json as written (25 significant digits)
    d1 = re.search(r'"name": "Yoshida4_json".*?"d": \[([-0-9.e]+)', text, re.S)
    digits = [i for i in range(d1.start(1), d1.end(1)) if text[i].isdigit()]
    for position in (2, 8, 12):  # one significant digit of d_1 changed by one
        k = digits[position]
        bad = tmp_path / f"changed{position}.json"
        bad.write_text(text[:k] + ("1" if text[k] == "0" else str(int(text[k]) - 1)) + text[k + 1:])
        r = run(LOAD, bad)
        assert r.returncode == 0, r.stderr
        assert "refused:" in r.stdout and "Yoshida4_json" in r.stdout and "tree [" in r.stdout, \
            r.stdout
    r = run(LOAD, path)  # negative control: the file as written loads
    assert r.stdout.strip() == "loaded", r.stdout + r.stderr
