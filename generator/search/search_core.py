"""The search both design scripts run (near_integrable.py, design_processed.py): random starts
from a fixed seed, feasibility by Gauss-Newton (scipy least_squares) on the imposed conditions,
then SLSQP on the objective with the independent imposed conditions as equalities, and the
best feasible optimum. A problem gives:

  imposed(x)   numpy array of the residuals that must vanish
  objective(x) the value to minimize (log of the predicted work)
  start(rng)   a random starting point (numpy Generator)
  free         the number of free parameters
and, for search(..., penalty=True), leading(x): the residuals whose 2-norm the objective
grows with (it is then minimized by Levenberg-Marquardt on the imposed residuals, weighted,
stacked on these, instead of SLSQP: least squares are what it is, and SLSQP stalls with a
processor's many parameters).
"""
import numpy as np
from scipy.linalg import qr
from scipy.optimize import least_squares, minimize


def independent_rows(problem, x):
    """Indices of a maximal independent set of imposed conditions at x (pivoted QR of J^T)."""
    r0, h = problem.imposed(x), 1e-7
    J = np.array([(problem.imposed(x + h * e) - r0) / h for e in np.eye(len(x))]).T
    _, R, piv = qr(J.T, pivoting=True)
    rank = int(np.sum(np.abs(np.diag(R)) > 1e-6 * abs(R[0, 0])))
    return sorted(piv[:rank])


def onto_conditions(problem, x, max_nfev=None, method="trf"):
    """Gauss-Newton from x onto the imposed conditions (to round-off)."""
    return least_squares(problem.imposed, x, xtol=1e-15, ftol=1e-15, gtol=1e-15,
                         max_nfev=max_nfev, method=method).x


def feasible(problem, rng, tol=1e-12, method="trf"):
    x = np.asarray(problem.start(rng), float)
    if len(problem.imposed(x)) < len(x):
        method = "trf"  # Levenberg-Marquardt needs as many residuals as unknowns
    x = onto_conditions(problem, x, max_nfev=400 if method == "trf" else 1000, method=method)
    return x if np.max(np.abs(problem.imposed(x))) < tol else None


def optimize(problem, x, tol=1e-13, maxiter=300):
    rows = independent_rows(problem, x)
    cons = {"type": "eq", "fun": lambda y: problem.imposed(y)[rows]}
    out = minimize(problem.objective, x, method="SLSQP", constraints=[cons],
                   options={"ftol": 1e-14, "maxiter": maxiter})
    y = onto_conditions(problem, out.x)  # back onto the conditions to round-off
    return y if np.max(np.abs(problem.imposed(y))) < tol else None


def optimize_leading(problem, x, tol=1e-13, weights=(1e2, 1e4, 1e6)):
    """Least squares of (weight * imposed, leading) for increasing weights (a continuation:
    a large weight at once stalls near the start), then back onto the conditions."""
    for weight in weights:
        def stacked(y):
            return np.concatenate([weight * problem.imposed(y), problem.leading(y)])
        x = least_squares(stacked, x, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                          max_nfev=3000).x
    y = onto_conditions(problem, x, method="lm" if len(problem.imposed(x)) >= len(x) else "trf")
    return y if np.max(np.abs(problem.imposed(y))) < tol else None


def search(problem, starts, seed=1, tol=1e-12, report=None, penalty=False, first=None):
    """The best (objective, x) over `starts` random starts, or None. penalty: feasibility by
    Levenberg-Marquardt and optimize_leading (else trf and SLSQP). first: a starting point
    tried before the random ones (e.g. a published method of the family)."""
    rng = np.random.default_rng(seed)
    best = None
    for n in range(starts + (first is not None)):
        if n == 0 and first is not None:
            x = onto_conditions(problem, np.asarray(first, float))
            x = x if np.max(np.abs(problem.imposed(x))) < tol else None
        else:
            x = feasible(problem, rng, tol, method="lm" if penalty else "trf")
        if x is None:
            continue
        if penalty:
            x = optimize_leading(problem, x, tol=tol / 10)
        elif problem.free > len(independent_rows(problem, x)):
            x = optimize(problem, x, tol=tol / 10)
        if x is None:
            continue
        f = problem.objective(x)
        if report:
            report(n, f)
        if best is None or f < best[0] - 1e-12:
            best = (f, x)
    return best
