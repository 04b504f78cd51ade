"""Symmetric splitting kernels with modified kicks, optionally processed: the family, its imposed
order conditions and the design objective (generator/search/design_processed.py searches it).

Kernel K (s kicks, layout ABA or BAB as in splitting_family.py): nodes c_i + c_(s+1-i) = 1,
weights d_i = d_(s+1-i), sum d_i = 1, and modified-kick coefficients e_i = e_(s+1-i) on the
stages listed in `modified` (0-based, first half and middle; the others e_i = 0): stage i kicks
p -= h (d_i grad U + h^2 e_i grad(|grad U|^2)), as methods.spec writes it.

Processor (m > 0 kicks): pi^-1 = drift z_1 h, kick (y_1, v_1), ..., drift z_m h, kick (y_m, v_m)
(methods.spec's pre_drift, pre_kick, pre_modified; v only with `pre_modified`), all free. The
method certified is psi = pi o K o pi^-1, the one splitting pi^-1, K, pi (sen_conditions.
composition, the generator's processing.cpp): its order is K's effective order.

Imposed: every condition of eq. (f) of power <= order for psi. Objective (the predicted work
per unit time to a tolerance, h -> 0): cost * C^(1/order), with C the generator's error
constant of psi (the 2-norm of every residual of power order + 1) and cost the kernel's force
evaluations per step, a grad(|grad U|^2) evaluation counted as g_cost gradients (a modified
kick costs 1 + g_cost plain ones; measured ~1.3 on sine-Gordon: docs/modified_kicks.md). The
processor's cost is paid at output only and is not counted.
"""
import math

import sen_conditions as sc


class ProcessedFamily:
    def __init__(self, stages, layout, order, modified, processor, pre_modified, g_cost):
        self.s, self.layout, self.order = stages, layout, order
        self.modified = sorted(modified)
        self.m, self.pre_modified, self.g_cost = processor, pre_modified, g_cost
        self.max_power = order + 1
        half = stages // 2
        self.n_nodes = half - (1 if layout == "BAB" else 0)
        self.n_weights = (stages + 1) // 2 - 1
        self.n_kernel = self.n_nodes + self.n_weights + len(self.modified)
        assert all(0 <= i < (stages + 1) // 2 for i in self.modified)

    def free(self):
        return self.n_kernel + self.m * (3 if self.pre_modified else 2)

    def cost(self):
        """Force evaluations per step, G counted as g_cost (BAB: the first and last kicks of
        consecutive steps merge into one, with their G terms)."""
        merged = self.layout == "BAB"
        grads = self.s - (1 if merged else 0)
        gs = sum(1 if 2 * i + 1 == self.s else 2 for i in self.modified)
        if merged and 0 in self.modified:
            gs -= 1
        return grads + self.g_cost * gs

    def start(self, rng):
        """A random starting point: kernel as near_integrable.py's, processor small."""
        kernel = [rng.uniform(-0.2, 0.6) for _ in range(self.n_nodes)] + \
                 [rng.uniform(-0.2, 0.5) for _ in range(self.n_weights)] + \
                 [rng.uniform(-0.02, 0.02) for _ in self.modified]
        pre = [rng.uniform(-0.5, 0.5) for _ in range(2 * self.m)] + \
              [rng.uniform(-0.02, 0.02) for _ in range(self.m if self.pre_modified else 0)]
        return kernel + pre

    def kernel(self, x, one=1.0):
        """(c, d, e) of K from the free parameters."""
        s, half = self.s, self.s // 2
        nodes = list(x[:self.n_nodes])
        if self.layout == "BAB":
            nodes = [0 * one] + nodes
        weights = list(x[self.n_nodes:self.n_nodes + self.n_weights])
        c = nodes + ([one / 2] if s % 2 else []) + [one - v for v in reversed(nodes)]
        if s % 2:
            d = weights + [one - 2 * sum(weights, 0 * one)] + list(reversed(weights))
        else:
            last = one / 2 - sum(weights, 0 * one)
            d = weights + [last, last] + list(reversed(weights))
        first = [0 * one] * ((s + 1) // 2)
        for i, v in zip(self.modified, x[self.n_nodes + self.n_weights:self.n_kernel]):
            first[i] = v
        e = first + list(reversed(first[:half]))
        assert len(c) == s == len(d) == len(e) and half == len(nodes)
        return c, d, e

    def processor(self, x):
        """(pre_drift, pre_kick, pre_modified or None) of pi^-1."""
        p, m = list(x[self.n_kernel:]), self.m
        return p[:m], p[m:2 * m], (p[2 * m:3 * m] if self.pre_modified else None)

    def sequence(self, x, one=1.0):
        c, d, e = self.kernel(x, one)
        if self.m == 0:
            return c, d, e
        return sc.composition(c, d, e, *self.processor(x))

    def residuals(self, x):
        c, d, e = self.sequence(list(x))
        return sc.residuals(c, d, self.max_power, e=e)

    def imposed(self, res):
        return [r for (_, _, _, power, _), r in zip(sc.order_conditions(self.max_power), res)
                if power <= self.order]

    def leading(self, res):
        """The residuals of power order + 1: the error constant is their 2-norm."""
        return [r for (_, _, _, power, _), r in zip(sc.order_conditions(self.max_power), res)
                if power == self.order + 1]

    def error_constant(self, res):
        return math.sqrt(sum(r * r for r in self.leading(res)))

    def log_work(self, res):
        return math.log(self.cost()) + math.log(self.error_constant(res)) / self.order
