"""Ways to compile the plant's RK4 step, measured side by side in one run (decision 0007).

    pip install cffi cython numba      # the candidates that are not already there (mypyc comes with mypy)
    python benchmarks/bench_kernel_candidates.py [--steps N]

Each candidate computes ``RigidBody.step_env`` (detumble.sim.attitude) and is called from Python the
way the plant would call it:

* ``C-API``: the project's kernel (``detumble.sim.plant_kernel``: plant_kernel.c, METH_FASTCALL);
* ``cffi``: the same C arithmetic behind cffi's API mode, doubles in, a ``double[7]`` out;
* ``mypyc``: attitude.py's ``step_env`` itself, compiled by mypyc;
* ``Cython``: the same Python compiled by Cython as it is, and a ``.pyx`` with ``cdef double`` locals;
* ``numba``: ``@njit`` on the same arithmetic, flat float arguments.

The C, Cython and numba bodies are generated from one written-out list of step_env's expressions
(``_rk4_lines``), so every candidate does the same operations. For each: time per step (best of 5 x N
calls), the cost of crossing the boundary (the same arguments and result, no arithmetic; where the
candidate has a no-op), whether N chained steps are bit-identical to the Python reference, and the
build or JIT time. The candidates are built in a temporary folder; nothing is installed. Timings are
never asserted.
"""
from __future__ import annotations

import argparse
import importlib
import inspect
import math
import os
import subprocess
import sys
import tempfile
import time

from detumble.sim import plant_kernel
from detumble.sim.attitude import RigidBody

INERTIA = ((2.0e-3, 1.0e-4, -5.0e-5), (1.0e-4, 3.0e-3, 8.0e-5), (-5.0e-5, 8.0e-5, 4.0e-3))
DT, M_B, B_N, GG, R_HAT = 0.05, (0.1, -0.05, 0.02), (2e-5, -1e-5, 3e-5), 3.8e-6, (0.6, 0.0, 0.8)
S0 = (0.8, 0.2, -0.4, 0.4, 0.3, -0.2, 0.4)


VARS = ("q0", "q1", "q2", "q3", "w1", "w2", "w3", "b1", "b2", "b3", "r1", "r2", "r3")


def _rk4_lines():
    """``(name, expression)`` of ``RigidBody.step_env``'s arithmetic written out, from the direction-cosine
    matrix to stage 4, operation for operation (plant_kernel.c's step as decision 0007 measured it; the
    combination is COMBINE below). ``bx`` .. ``rz`` are arguments of the candidates."""
    out = [
        ("c11", "q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3"), ("c12", "2.0 * (q1 * q2 + q0 * q3)"),
        ("c13", "2.0 * (q1 * q3 - q0 * q2)"), ("c21", "2.0 * (q1 * q2 - q0 * q3)"),
        ("c22", "q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3"), ("c23", "2.0 * (q2 * q3 + q0 * q1)"),
        ("c31", "2.0 * (q1 * q3 + q0 * q2)"), ("c32", "2.0 * (q2 * q3 - q0 * q1)"),
        ("c33", "q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3"),
    ]
    for v in ("b", "r"):
        out += [(f"{v}{i}", f"c{i}1 * {v}x + c{i}2 * {v}y + c{i}3 * {v}z") for i in (1, 2, 3)]
    out.append(("a", "0.5 * dt"))
    for s in (1, 2, 3, 4):
        x = {v: v if s == 1 else f"{v}_{s}" for v in VARS}
        if s > 1:
            step = "dt" if s == 4 else "a"
            out += [(x[v], f"{v} + {step} * k{s - 1}_{i}") for i, v in enumerate(VARS)]
        q0, q1, q2, q3, w1, w2, w3, b1, b2, b3, r1, r2, r3 = (x[v] for v in VARS)
        sv, hv, gv = ([f"{c}{i}_{s}" for i in (1, 2, 3)] for c in "shg")
        out += [(sv[i], f"j{i + 1}1 * {r1} + j{i + 1}2 * {r2} + j{i + 1}3 * {r3}") for i in range(3)]
        out += [(hv[i], f"j{i + 1}1 * {w1} + j{i + 1}2 * {w2} + j{i + 1}3 * {w3} + h{'xyz'[i]}") for i in range(3)]
        out += [
            (gv[0], f"tx + my * {b3} - mz * {b2} + g * "
                     f"({r2} * {sv[2]} - {r3} * {sv[1]}) - ({w2} * {hv[2]} - {w3} * {hv[1]})"),
            (gv[1], f"ty + mz * {b1} - mx * {b3} + g * "
                     f"({r3} * {sv[0]} - {r1} * {sv[2]}) - ({w3} * {hv[0]} - {w1} * {hv[2]})"),
            (gv[2], f"tz + mx * {b2} - my * {b1} + g * "
                     f"({r1} * {sv[1]} - {r2} * {sv[0]}) - ({w1} * {hv[1]} - {w2} * {hv[0]})"),
        ]
        k = [
            f"0.5 * (-{q1} * {w1} - {q2} * {w2} - {q3} * {w3})",
            f"0.5 * ({q0} * {w1} + {q2} * {w3} - {q3} * {w2})",
            f"0.5 * ({q0} * {w2} - {q1} * {w3} + {q3} * {w1})",
            f"0.5 * ({q0} * {w3} + {q1} * {w2} - {q2} * {w1})",
            *(f"i{i + 1}1 * {gv[0]} + i{i + 1}2 * {gv[1]} + i{i + 1}3 * {gv[2]}" for i in range(3)),
            f"{b2} * {w3} - {b3} * {w2}", f"{b3} * {w1} - {b1} * {w3}", f"{b1} * {w2} - {b2} * {w1}",
            f"{r2} * {w3} - {r3} * {w2}", f"{r3} * {w1} - {r1} * {w3}", f"{r1} * {w2} - {r2} * {w1}",
        ]
        out += [(f"k{s}_{i}", e) for i, e in enumerate(k[:7] if s == 4 else k)]
    return out


COMBINE = [
    ("c", "dt / 6.0"),
    ("p0", "q0 + c * (k1_0 + 2.0 * (k2_0 + k3_0) + k4_0)"),
    ("p1", "q1 + c * (k1_1 + 2.0 * (k2_1 + k3_1) + k4_1)"),
    ("p2", "q2 + c * (k1_2 + 2.0 * (k2_2 + k3_2) + k4_2)"),
    ("p3", "q3 + c * (k1_3 + 2.0 * (k2_3 + k3_3) + k4_3)"),
    ("n", "1.0 / sqrt(p0 * p0 + p1 * p1 + p2 * p2 + p3 * p3)"),
]
RESULT = ("(p0 * n, p1 * n, p2 * n, p3 * n, w1 + c * (k1_4 + 2.0 * (k2_4 + k3_4) + k4_4), "
          "w2 + c * (k1_5 + 2.0 * (k2_5 + k3_5) + k4_5), w3 + c * (k1_6 + 2.0 * (k2_6 + k3_6) + k4_6))")
CONSTS = "j11 j12 j13 j21 j22 j23 j31 j32 j33 i11 i12 i13 i21 i22 i23 i31 i32 i33 hx hy hz".split()
ARGS = "q0 q1 q2 q3 w1 w2 w3 dt mx my mz bx by bz g rx ry rz".split()


def _generated_lines(indent: str, decl: str = "") -> str:
    lines = [f"{indent}{decl}{k} = {v}" for k, v in _rk4_lines() + COMBINE]
    return "\n".join(lines) + "\n"


CFFI_SOURCE = """
#include <math.h>
static double K[21];
/* static: a global "step" would be glibc's obsolete regexp step() at run time */
static void set_body(const double *k) { for (int i = 0; i < 21; i++) K[i] = k[i]; }
static void nothing(%(params)s, double *out) { out[0] = q0; }
static void step(%(params)s, double *out) {
    const double %(consts)s;
    const double tx = 0.0, ty = 0.0, tz = 0.0;
%(body)s    const double r[7] = %(result)s;
    for (int i = 0; i < 7; i++) out[i] = r[i];
}
"""


def _write(folder: str, name: str, text: str) -> str:
    path = os.path.join(folder, name)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)
    return path


def build_cffi(folder: str):
    import cffi

    params = ", ".join(f"double {a}" for a in ARGS)
    ffi = cffi.FFI()
    ffi.cdef(f"void set_body(const double *k); void nothing({params}, double *out); void step({params}, double *out);")
    consts = ", ".join(f"{c} = K[{i}]" for i, c in enumerate(CONSTS))
    body = _generated_lines("    ", "const double ").replace("\n", ";\n")
    ffi.set_source("cand_cffi", CFFI_SOURCE % {"params": params, "consts": consts, "body": body,
                                               "result": "{" + RESULT[1:-1] + "}"},
                   extra_compile_args=list(plant_kernel.COMPILE_FLAGS))
    ffi.compile(tmpdir=folder)
    return importlib.import_module("cand_cffi")


def _python_module() -> str:
    src = inspect.getsource(RigidBody.step_env)
    return ("from __future__ import annotations\nimport math\n"
            "State = tuple[float, float, float, float, float, float, float]\nVec3 = tuple[float, float, float]\n\n"
            "class RigidBody:\n"
            "    def __init__(self, j9: tuple[float, ...], ji9: tuple[float, ...], h: Vec3) -> None:\n"
            "        self._j = j9\n        self._jinv = ji9\n        self.wheel_momentum_B = h\n\n" + src)


def build_mypyc(folder: str):
    _write(folder, "cand_mypyc.py", _python_module().replace("tuple[float, ...]", "tuple[float, float, float, "
                                                             "float, float, float, float, float, float]"))
    subprocess.run([sys.executable, "-m", "mypyc", "cand_mypyc.py"], cwd=folder, check=True, capture_output=True)
    os.remove(os.path.join(folder, "cand_mypyc.py"))  # import the compiled module, not the source
    return importlib.import_module("cand_mypyc")


def _cythonize(folder: str, name: str):
    subprocess.run([sys.executable, "-m", "cython", "-3", name], cwd=folder, check=True, capture_output=True)
    subprocess.run([sys.executable, "-c", "from setuptools import setup, Extension; import sys; "
                    f"setup(ext_modules=[Extension('{name.split('.')[0]}', ['{name.split('.')[0]}.c'], "
                    "extra_compile_args=['-O2', '-ffp-contract=off'])], script_args=['build_ext', '--inplace'])"],
                   cwd=folder, check=True, capture_output=True)
    for ext in (".py", ".pyx"):
        if os.path.exists(os.path.join(folder, name.split(".")[0] + ext)):
            os.remove(os.path.join(folder, name.split(".")[0] + ext))
    return importlib.import_module(name.split(".")[0])


def build_cython_as_is(folder: str):
    _write(folder, "cand_cy_pure.py", _python_module())
    return _cythonize(folder, "cand_cy_pure.py")


def build_cython_typed(folder: str):
    pyx = ("# cython: language_level=3\nfrom libc.math cimport sqrt\n"
           f"cdef double {', '.join(CONSTS)}\n"
           "def set_body(k):\n"
           f"    global {', '.join(CONSTS)}\n    {', '.join(CONSTS)} = k\n"
           "def step(tuple s, double dt, tuple m, tuple b, double g, tuple r):\n"
           "    cdef double q0 = s[0], q1 = s[1], q2 = s[2], q3 = s[3], w1 = s[4], w2 = s[5], w3 = s[6]\n"
           "    cdef double mx = m[0], my = m[1], mz = m[2], bx = b[0], by = b[1], bz = b[2]\n"
           "    cdef double rx = r[0], ry = r[1], rz = r[2], tx = 0.0, ty = 0.0, tz = 0.0\n"
           + _generated_lines("    ", "cdef double ") + f"    return {RESULT}\n")
    _write(folder, "cand_cy_typed.pyx", pyx)
    return _cythonize(folder, "cand_cy_typed.pyx")


NUMBA_SOURCE = """import math
from numba import njit
sqrt = math.sqrt

@njit(cache=True)
def step(%(consts)s, %(args)s):
    tx = 0.0
    ty = 0.0
    tz = 0.0
%(body)s    return %(result)s
"""


def _numba_source() -> str:
    return NUMBA_SOURCE % {"consts": ", ".join(CONSTS), "args": ", ".join(ARGS), "body": _generated_lines("    "),
                           "result": RESULT}


def numba_warm_up(folder: str) -> tuple[float, float]:
    """Seconds from a fresh interpreter to the first result: with an empty JIT cache, then with it filled."""
    _write(folder, "cand_numba.py", _numba_source())
    probe = ("import time; t0 = time.perf_counter(); import cand_numba; "
             f"cand_numba.step(*([1.0] * {len(CONSTS)}), *([0.5] * {len(ARGS)})); print(time.perf_counter() - t0)")
    times = []
    for _ in range(2):
        done = subprocess.run([sys.executable, "-c", probe], cwd=folder, check=True, capture_output=True, text=True)
        times.append(float(done.stdout.strip()))
    return times[0], times[1]


def _timed(fn, n: int) -> float:
    best = math.inf
    for _ in range(5):
        t0 = time.perf_counter()
        fn(n)
        best = min(best, time.perf_counter() - t0)
    return best / n * 1e6


def _tuple_calls(f):
    """``(one step, a loop of c steps)`` for a candidate called as ``f(state, dt, m_B, b_N, gg, r_hat_N)``."""
    def step(s):
        return f(s, DT, M_B, B_N, GG, R_HAT)

    def loop(c):
        s = S0
        for _ in range(c):
            f(s, DT, M_B, B_N, GG, R_HAT)
    return step, loop


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=20_000)
    n = ap.parse_args().steps
    body = RigidBody(INERTIA, (1e-5, -2e-5, 3e-5))
    consts = body._j + body._jinv + body.wheel_momentum_B
    ref, s = [], S0
    for _ in range(n):
        s = body.step_env(s, DT, M_B, B_N, GG, R_HAT)
        ref.append(s)
    rows = []

    def check(name, step, loop, boundary=None, build=""):
        got, s = [], S0
        for _ in range(n):
            s = step(s)
            got.append(s)
        same = "yes" if got == ref else "NO"
        rows.append((name, _timed(loop, n), _timed(boundary, n) if boundary else None, same, build))

    check("Python (reference)", *_tuple_calls(body.step_env))

    status = plant_kernel.load()
    if status.module is not None:
        k = status.module.Kernel(body._j, body._jinv, body.wheel_momentum_B)
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            plant_kernel._build(os.path.join(tmp, "k" + plant_kernel._ext_suffix()), "bench")
        check("C-API (plant_kernel.c)", *_tuple_calls(k.step_env), build=f"gcc {time.perf_counter() - t0:.2f} s")
    else:
        rows.append(("C-API (plant_kernel.c)", None, None, "-", status.reason))

    with tempfile.TemporaryDirectory() as folder:
        sys.path.insert(0, folder)
        mx, my, mz = M_B
        bx, by, bz = B_N
        rx, ry, rz = R_HAT
        for name, build in (("cffi (API mode)", build_cffi), ("mypyc (attitude.py as is)", build_mypyc),
                            ("Cython (attitude.py as is)", build_cython_as_is),
                            ("Cython (cdef double .pyx)", build_cython_typed)):
            t0 = time.perf_counter()
            try:
                mod = build(folder)
            except (ImportError, OSError, subprocess.CalledProcessError) as exc:
                rows.append((name, None, None, "-", f"not built: {type(exc).__name__}"))
                continue
            built = f"{time.perf_counter() - t0:.1f} s"
            if name.startswith("cffi"):
                ffi, lib = mod.ffi, mod.lib
                lib.set_body(ffi.new("double[21]", consts))
                out = ffi.new("double[7]")
                unpack = ffi.unpack

                def cffi_step(s, lib=lib, out=out, unpack=unpack):
                    lib.step(*s, DT, mx, my, mz, bx, by, bz, GG, rx, ry, rz, out)
                    return tuple(unpack(out, 7))

                def cffi_calls(fn, out=out, unpack=unpack):
                    def loop(c):
                        s = S0
                        for _ in range(c):
                            q0, q1, q2, q3, w1, w2, w3 = s
                            fn(q0, q1, q2, q3, w1, w2, w3, DT, mx, my, mz, bx, by, bz, GG, rx, ry, rz, out)
                            tuple(unpack(out, 7))
                    return loop
                check(name, cffi_step, cffi_calls(lib.step), cffi_calls(lib.nothing), built)
            elif hasattr(mod, "set_body"):
                mod.set_body(consts)
                check(name, *_tuple_calls(mod.step), build=built)
            else:
                rb = mod.RigidBody(body._j, body._jinv, body.wheel_momentum_B)
                check(name, *_tuple_calls(rb.step_env), build=built)
        try:
            cold, cached = numba_warm_up(folder)
            mod = importlib.import_module("cand_numba")

            def numba_step(s, f=mod.step):
                return f(*consts, *s, DT, mx, my, mz, bx, by, bz, GG, rx, ry, rz)

            def numba_loop(c, f=mod.step):
                s = S0
                for _ in range(c):
                    q0, q1, q2, q3, w1, w2, w3 = s
                    f(*consts, q0, q1, q2, q3, w1, w2, w3, DT, mx, my, mz, bx, by, bz, GG, rx, ry, rz)
            check("numba (@njit, flat args)", numba_step, numba_loop,
                  build=f"first call in a new process {cold:.2f} s, {cached:.2f} s with its cache")
        except (ImportError, OSError, subprocess.CalledProcessError) as exc:
            rows.append(("numba (@njit, flat args)", None, None, "-", f"not built: {type(exc).__name__}"))
    print(f"{'candidate':30s} {'us/step':>8s} {'boundary us':>12s}  bit-identical ({n} steps)  build / warm-up")
    for name, t, b, same, build in rows:
        ts = f"{t:8.2f}" if t is not None else f"{'-':>8s}"
        bs = f"{b:12.2f}" if b is not None else f"{'-':>12s}"
        print(f"{name:30s} {ts} {bs}  {same:24s} {build}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
