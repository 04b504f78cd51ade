"""Symmetric plain-kick splitting methods with free parameters: the family, its imposed order
conditions and the design objective (generator/search/near_integrable.py searches it).

Family (s kicks, layout ABA or BAB): nodes c_i + c_(s+1-i) = 1, weights d_i = d_(s+1-i),
sum d_i = 1; BAB has c_1 = 0, c_s = 1 (the runtime and the peers merge the last kick of a step
with the first of the next: s - 1 gradients per step). Free: the first half of the nodes
(except c_1 = 0 for BAB) and of the weights; the middle weight (s odd) or the last of the
first half (s even) makes sum d_i = 1.

Imposed: every condition of eq. (f) (sen_conditions.py) of power <= order, and for the trees
with K f-vertices every condition of power <= g_K (generalized order for H = A + eps B).

Objective (the predicted work to a tolerance): with the generator's error constants C_K (the
2-norm of the residuals of the trees with K f-vertices at power g_K + 1) the global error over
unit time is modelled as E(h) = sum_K eps^K C_K h^(g_K), and the work as the gradients per
unit time, (gradients per step) / h*, where E(h*) = tol. For one K this is the standard
effective error (gradients) * (eps^K C_K / tol)^(1/g_K).
"""
import math

import sen_conditions as sc


class Family:
    def __init__(self, stages, layout, order, generalized, max_power=None, kmax=3):
        # kmax: trees with more f-vertices are not evaluated (None: all, for the classical
        # error constant); every condition of power <= 6 has at most 3.
        self.s, self.layout, self.order, self.kmax = stages, layout, order, kmax
        self.generalized = list(generalized)
        need = max([order] + self.generalized) + 1
        self.max_power = need if max_power is None else max_power
        half = stages // 2
        self.n_nodes = half - (1 if layout == "BAB" else 0)
        self.n_weights = (stages + 1) // 2 - 1
        self.gradients = stages - 1 if layout == "BAB" else stages

    def free(self):
        return self.n_nodes + self.n_weights

    def method(self, x, one=1.0):
        """(c, d) from the free parameters x = (first-half nodes, first-half weights)."""
        s, half = self.s, self.s // 2
        nodes = list(x[:self.n_nodes])
        if self.layout == "BAB":
            nodes = [0 * one] + nodes
        weights = list(x[self.n_nodes:])
        c = nodes + ([one / 2] if s % 2 else []) + [one - v for v in reversed(nodes)]
        if s % 2:
            middle = one - 2 * sum(weights, 0 * one)
            d = weights + [middle] + list(reversed(weights))
        else:
            last = one / 2 - sum(weights, 0 * one)
            d = weights + [last, last] + list(reversed(weights))
        assert len(c) == s == len(d) and half == len(nodes)
        return c, d

    def imposed(self, res):
        """The residuals this family must zero, from sen_conditions.residuals' list."""
        trees = sc.sen_trees(self.max_power)
        out = []
        for (t, _, _, power, _), r in zip(sc.order_conditions(self.max_power), res):
            K = trees[t].fvertices
            gK = self.generalized[K - 1] if K <= len(self.generalized) else self.order
            if power <= max(self.order, gK) and r is not None:
                out.append(r)
        return out

    def constants(self, res, kmax=3):
        """[(K, C_K, g_K)] for K = 1 .. max(kmax, len(generalized)) (the generator's norms):
        g_K as imposed, or for the K beyond `generalized` the last power before the first
        nonzero residual (> 1e-12) of the trees with K f-vertices, within max_power."""
        trees = sc.sen_trees(self.max_power)
        norms = {}
        for (t, _, _, power, _), r in zip(sc.order_conditions(self.max_power), res):
            if r is None:
                continue
            key = (trees[t].fvertices, power)
            norms[key] = norms.get(key, 0.0) + float(r) ** 2
        out = []
        for K in range(1, max(kmax, len(self.generalized)) + 1):
            if K <= len(self.generalized):
                gK = self.generalized[K - 1]
            else:
                failing = [p for (k, p), v in norms.items() if k == K and math.sqrt(v) > 1e-12]
                if not failing:
                    continue
                gK = min(failing) - 1
            out.append((K, math.sqrt(norms.get((K, gK + 1), 0.0)), gK))
        return out

    def error_constant(self, res):
        """The 2-norm of the residuals of every condition of power order + 1."""
        return math.sqrt(sum(float(r) ** 2 for (_, _, _, power, _), r in
                             zip(sc.order_conditions(self.max_power), res)
                             if power == self.order + 1))

    def classical_order(self, res):
        return min(g for _, _, g in self.constants(res))


def work(constants, gradients, eps, tol):
    """Gradients per unit time to reach tol under E(h) = sum_K eps^K C_K h^(g_K)."""
    def error(h):
        return sum(eps ** K * C * h ** g for K, C, g in constants)
    lo, hi = 1e-6, 1e3
    if error(hi) <= tol:
        return gradients / hi
    for _ in range(200):  # bisection in log h: error is increasing in h
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if error(mid) <= tol else (lo, mid)
    return gradients / lo
