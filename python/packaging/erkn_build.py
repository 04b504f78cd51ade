"""PEP 517 backend for `pip install .`: configures the project's CMake with only the Python
module, builds the target _erkn, and zips <build>/python/erkn into a wheel. Standard library
only, so pip's isolated build environment needs nothing from an index.

ERKN_CMAKE_ARGS (environment) adds arguments to the configure step, e.g. a compiler launcher."""

import base64
import hashlib
import os
import pathlib
import re
import shlex
import subprocess
import sys
import sysconfig
import tempfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(erkn VERSION ([0-9.]+)", text).group(1)


def _tag():
    py = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{py}-{py}-{platform}"


def _metadata(version):
    return ("Metadata-Version: 2.1\nName: erkn\nVersion: " + version + "\n"
            "Summary: Symplectic ERKN integrators for q'' + M q = -grad U(q)\n"
            "Requires-Python: >=3.8\nRequires-Dist: numpy\n")


def _build_package(build):
    """Runs CMake; returns <build>/python/erkn."""
    # pip's isolated environment hides the interpreter's own site-packages (NumPy) through
    # PYTHONPATH and PYTHONNOUSERSITE; CMake checks that the interpreter imports NumPy, so the
    # configure step runs without them.
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONNOUSERSITE")}
    off = ["GENERATOR", "TESTS", "EXPERIMENTS", "BENCHMARKS"]
    configure = (["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                  f"-DPython_EXECUTABLE={sys.executable}", "-DERKN_WITH_MPI=OFF"]
                 + [f"-DERKN_BUILD_{name}=OFF" for name in off]
                 + shlex.split(os.environ.get("ERKN_CMAKE_ARGS", "")))
    subprocess.run(configure, check=True, env=env, stdout=sys.stderr)
    subprocess.run(["cmake", "--build", str(build), "--target", "_erkn", "-j",
                    str(os.cpu_count() or 1)], check=True, env=env, stdout=sys.stderr)
    package = build / "python" / "erkn"
    if not any(package.glob("_erkn*.so")):
        raise RuntimeError(f"CMake built no extension in {package} (see its messages above)")
    return package


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    version, tag = _version(), _tag()
    dist_info = f"erkn-{version}.dist-info"
    files = {}
    with tempfile.TemporaryDirectory() as tmp:
        package = _build_package(pathlib.Path(tmp) / "build")
        for path in sorted(package.iterdir()):
            if path.suffix == ".py" or path.name.startswith("_erkn"):
                files[f"erkn/{path.name}"] = path.read_bytes()
    files[f"{dist_info}/METADATA"] = _metadata(version).encode()
    files[f"{dist_info}/WHEEL"] = ("Wheel-Version: 1.0\nGenerator: erkn_build\n"
                                   f"Root-Is-Purelib: false\nTag: {tag}\n").encode()
    record = [_record_line(name, data) for name, data in files.items()]
    files[f"{dist_info}/RECORD"] = ("\n".join(record + [f"{dist_info}/RECORD,,"]) + "\n").encode()
    name = f"erkn-{version}-{tag}.whl"
    with zipfile.ZipFile(pathlib.Path(wheel_directory) / name, "w", zipfile.ZIP_DEFLATED) as z:
        for path, data in files.items():
            z.writestr(path, data)
    return name


def get_requires_for_build_wheel(config_settings=None):
    return []
