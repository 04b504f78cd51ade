"""The generator's order conditions for explicit splitting methods, in floating point.

A transcription of generator/src/trees.cpp (SEN-trees, eq. (f)'s conditions) and of
generator/src/certify.cpp (explicit_series, the elementary weights, the residuals and the error
constants) for the explicit family: the exact flow of q'' + M q = 0 over h (c_(i+1) - c_i)
alternated with kicks p -= h (d_i grad U(Q_i) + h^2 e_i grad(|grad U|^2)(Q_i)) (e = None: plain
kicks), and processed methods as the one splitting pi^-1, K, pi (composition()). Same trees, same conditions, same norms: the
error constant of order p is the 2-norm of the residuals of every condition of power p + 1,
the generalized one for eps^K the 2-norm over the trees with K f-vertices at power g_K + 1.
check_against_generator.py compares these numbers with generated/src/tables.cpp.

Numbers are numpy float64 arrays, or mpmath mpf through the `one` argument (mpf(1)) where
the search refines a solution.
"""
import functools
import math
from fractions import Fraction

# certify.hpp's modified_kick_weight: grad(|grad U|^2) = 2 f' f (f = -grad U), so the spec's
# -h^3 e grad(|grad U|^2) is h^3 (-2 e) f' f, the term the tree expansion weighs.
MODIFIED_KICK_WEIGHT = -2


class Tree:
    def __init__(self):
        self.p_leaves = 0
        self.f_children = []  # (k, index of the subtree): reached through M^k
        self.size = 0  # its power of h in f(Q_i)
        self.fvertices = 1
        self.kappa = Fraction(1)

    def rho_factorial_over_gamma(self):
        return self.kappa * math.factorial(self.size)


def _make_tree(children, types, trees):
    t = Tree()
    for ident in children:
        k, sub, size = types[ident]
        t.size += size
        if sub < 0:
            t.p_leaves += 1
            continue
        s = trees[sub]
        t.f_children.append((k, sub))
        t.fvertices += s.fvertices
        sign = -1 if k % 2 else 1
        t.kappa *= s.kappa * sign * Fraction(math.factorial(s.size),
                                             math.factorial(2 * k + s.size + 2))
    return t


@functools.lru_cache(None)
def sen_trees(max_rho):
    """Every SEN-tree with rho <= max_rho, subtrees first (trees.cpp's sen_trees)."""
    trees, types = [], [(0, -1, 1)]  # child types (k, tree, size); a p-leaf first
    for n in range(max_rho):
        for k in range(0, max(0, (n - 2) // 2 + 1) if n >= 2 else 0):
            types += [(k, t, n) for t in range(len(trees)) if trees[t].size == n - 2 - 2 * k]
        fresh, chosen = [], []

        def choose(start, rest):
            if rest == 0:
                fresh.append(_make_tree(chosen, types, trees))
                return
            for ident in range(start, len(types)):
                if types[ident][2] <= rest:
                    chosen.append(ident)
                    choose(ident, rest - types[ident][2])
                    chosen.pop()
        choose(0, n)
        trees += fresh
    return tuple(trees)


@functools.lru_cache(None)
def order_conditions(max_power):
    """(tree, bbar, j, power, rhs as a float) by increasing power (trees.cpp)."""
    trees = sen_trees(max_power)
    out = []
    for power in range(1, max_power + 1):
        for t, tree in enumerate(trees):
            for bbar in (False, True):
                rho = tree.size + 1
                twice_j = power - rho - (1 if bbar else 0)
                if twice_j < 0 or twice_j % 2:
                    continue
                j = twice_j // 2
                m = rho + (1 if bbar else 0)
                rhs = tree.rho_factorial_over_gamma() * (-1) ** j / math.factorial(2 * j + m)
                out.append((t, bbar, j, power, rhs))
    return tuple(out)


def _series(K, w, m, terms, one):
    """K w^m phi_m(w^2 V) as coefficients of V^0 .. V^(terms-1)."""
    return [K * w ** (m + 2 * j) * (-1) ** j / math.factorial(2 * j + m) * one
            for j in range(terms)]


def residuals(c, d, max_power, one=1.0, fast=True, kmax=None, e=None):
    """Residual (lhs - rhs) of every condition of power <= max_power, in order_conditions'
    order, for the explicit method with nodes c and weights d (certify.cpp). Floats with
    fast: numpy (the same sums as matrix products); else plain Python lists (mpf: one=mpf(1)).
    kmax (numpy only): the trees with more f-vertices are skipped, their residuals None.
    e: the modified-kick coefficients (None: plain kicks); a stage's f'(Q_i) f(Q_i) term
    carries et_i = MODIFIED_KICK_WEIGHT * e_i (certify.hpp's modified_kick_weight)."""
    if one == 1.0 and fast:
        return _residuals_numpy(c, d, max_power, kmax, e)
    s, terms = len(c), max_power // 2 + 1
    trees = sen_trees(max_power)
    et = [MODIFIED_KICK_WEIGHT * x for x in (e if e is not None else [0 * one] * s)]
    b, bbar, abar = _plain_kernels(c, d, terms, one)
    b_mod, bbar_mod, abar_mod = _plain_kernels(c, et, terms, one)
    plain, mod = [], []
    for tree in trees:
        leaves = [c[i] ** tree.p_leaves * one for i in range(s)]
        S = [[sum((abar[i][j][k] * plain[sub][j] + abar_mod[i][j][k] * mod[sub][j]
                   for j in range(i)), 0 * one) for i in range(s)]
             for k, sub in tree.f_children]
        plain.append([leaves[i] * _product(x[i] for x in S) * one for i in range(s)])
        mod.append([leaves[i] * _psi_sum(tree, S, plain, i, one) for i in range(s)])
    out = []
    for t, bb, j, _, rhs in order_conditions(max_power):
        coef, cmod = (bbar, bbar_mod) if bb else (b, b_mod)
        out.append(sum(coef[i][j] * plain[t][i] + cmod[i][j] * mod[t][i] for i in range(s))
                   - rhs * one)
    return out


def _plain_kernels(c, d, terms, one):
    """b, bbar, abar of the explicit method (c, d) as series in V (certify.cpp's
    explicit_series); with d = et the kernels of the modified terms."""
    s = len(c)
    b = [_series(d[i], one - c[i], 0, terms, one) for i in range(s)]
    bbar = [_series(d[i], one - c[i], 1, terms, one) for i in range(s)]
    abar = [[_series(d[j], c[i] - c[j], 1, terms, one) for j in range(i)] for i in range(s)]
    return b, bbar, abar


def _product(values):
    out = 1
    for v in values:
        out = out * v
    return out


def _psi_sum(tree, S, plain, i, one):
    """Psi_i(tau) / c_i^(p-leaves) (certify.cpp): the weight of f'(Q_i) f(Q_i), a sum over
    the root's children r reached through M^0 of Phi_i(sub_r) times the other children's S."""
    total = 0 * one
    for r, (k, sub) in enumerate(tree.f_children):
        if k == 0:
            total = total + plain[sub][i] * _product(S[q][i] for q in range(len(S)) if q != r)
    return total


def _kernels(terms):
    import numpy as np
    """[V^j] of w^m phi_m(w^2 V) = (-1)^j w^(2j+m) / (2j+m)!: signs/factorials, m = 0, 1."""
    return [np.array([(-1) ** j / math.factorial(2 * j + m) for j in range(terms)])
            for m in (0, 1)]


def _numpy_kernels(c, d, terms):
    """b[i, j], bbar[i, j] (coefficients of V^j) and abar[k][i, j] of (c, d), as in
    _plain_kernels."""
    import numpy as np
    k0, k1 = _kernels(terms)
    j = np.arange(terms)
    w = 1 - c
    b = d[:, None] * w[:, None] ** (2 * j) * k0
    bbar = d[:, None] * w[:, None] ** (2 * j + 1) * k1
    diff = c[:, None] - c[None, :]
    lower = np.tril(np.ones((len(c), len(c))), -1)
    abar = [lower * d[None, :] * diff ** (2 * k + 1) * k1[k] for k in range(terms)]
    return b, bbar, abar


def _residuals_numpy(c, d, max_power, kmax=None, e=None):
    import numpy as np
    c, d = np.asarray(c, float), np.asarray(d, float)
    s, terms = len(c), max_power // 2 + 1
    b, bbar, abar = _numpy_kernels(c, d, terms)
    modified = e is not None
    if modified:
        et = MODIFIED_KICK_WEIGHT * np.asarray(e, float)
        b_mod, bbar_mod, abar_mod = _numpy_kernels(c, et, terms)
    trees = sen_trees(max_power)
    plain = np.zeros((len(trees), s))
    mod = np.zeros((len(trees), s))
    skipped = np.zeros(len(trees), bool)
    for n, tree in enumerate(trees):
        if kmax is not None and tree.fvertices > kmax:
            skipped[n] = True
            continue
        S = [abar[k] @ plain[sub] + (abar_mod[k] @ mod[sub] if modified else 0)
             for k, sub in tree.f_children]
        leaves = c ** tree.p_leaves
        plain[n] = leaves * _product(S)
        if modified:
            mod[n] = leaves * _product_rule(tree, S, plain, s)
    t, bb, jj, rhs = _condition_arrays(max_power)
    sums = np.where(bb, (plain @ bbar)[t, jj], (plain @ b)[t, jj]) - rhs
    if modified:
        sums += np.where(bb, (mod @ bbar_mod)[t, jj], (mod @ b_mod)[t, jj])
    return [None if skipped[i] else float(v) for i, v in zip(t, sums)]


def _product_rule(tree, S, plain, s):
    """_psi_sum over every stage at once (numpy rows)."""
    import numpy as np
    total = np.zeros(s)
    for r, (k, sub) in enumerate(tree.f_children):
        if k == 0:
            total = total + plain[sub] * _product(S[q] for q in range(len(S)) if q != r)
    return total


@functools.lru_cache(None)
def _condition_arrays(max_power):
    import numpy as np
    oc = order_conditions(max_power)
    return (np.array([o[0] for o in oc]), np.array([o[1] for o in oc]),
            np.array([o[2] for o in oc]), np.array([float(o[4]) for o in oc]))


def leading_norms(c, d, powers, max_power, one=1.0, fast=True, e=None):
    """{(K, power): 2-norm of the residuals at `power` over the trees with K f-vertices
    (K = 0: every tree)} for the (K, power) in `powers` (certify.cpp's leading_norm)."""
    trees = sen_trees(max_power)
    res = residuals(c, d, max_power, one, fast, e=e)
    sums = {kp: 0 * one for kp in powers}
    for (t, _, _, power, _), r in zip(order_conditions(max_power), res):
        for K, p in powers:
            if p == power and (K == 0 or trees[t].fvertices == K):
                sums[(K, p)] += r * r
    return {kp: v ** 0.5 for kp, v in sums.items()}


def composition(c, d, e, pre_drift, pre_kick, pre_modified=None):
    """psi = pi o K o pi^-1 as one explicit method (processing.cpp's composition): the kicks of
    pi^-1 at their cumulative drifts, K's at T + c_i (T the total pre-drift), pi's at 1 + the
    pre-positions in reverse order with negated kick and modified coefficients. Returns
    (c, d, e), e None when neither K nor pi^-1 has modified kicks."""
    m = len(pre_kick)
    at, position = [], 0 * pre_drift[0]
    for k in range(m):
        position = position + pre_drift[k]
        at.append(position)
    T = sum(pre_drift, 0 * pre_drift[0])
    modified = e is not None or pre_modified is not None
    pe = list(pre_modified) if pre_modified is not None else [0 * T] * m
    ke = list(e) if e is not None else [0 * T] * len(c)
    cc = at + [T + x for x in c] + [1 + at[k] for k in reversed(range(m))]
    dd = list(pre_kick) + list(d) + [-pre_kick[k] for k in reversed(range(m))]
    ee = pe + ke + [-pe[k] for k in reversed(range(m))]
    return cc, dd, (ee if modified else None)
