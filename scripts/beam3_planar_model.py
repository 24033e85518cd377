#!/usr/bin/env python3
"""Planar model of tests/mbdyn_files/beam3_tip_couple.mbd (two beam3 elements, static
nodes, tip couple ramped over [0, 1] s, method ms 0.6) in the two formulations of the
three-node beam's rotation field (tests/multibody/beam_rotation.rs):

- romdyn: total rotation interpolated relative to the middle node,
  phi_s = phi_2 + 2 atan(sum N_i tan((phi_i - phi_2)/2)), kappa = d phi_s / ds;
- MBDyn 1.7.3 (beam.cc, strnode.cc), incremental: per step the nodes' predicted
  increments g_ref (ms predictor on the Gibbs parameters measured from the previous
  orientation) and Newton's correction g from the predicted orientation are interpolated
  separately; the section angle and curvature accumulate
  phi_s = phi_s,prev + 2 atan(N.g_ref/2) + 2 atan(N.g/2),
  kappa = kappa_prev + (N'.g_ref)/(1 + (N.g_ref)^2/4) + (N'.g)/(1 + (N.g)^2/4).

Prints the tip's final position for 1, 10 and 100 load steps; MBDyn 1.7.3's numbers are
in tests/multibody/beam_rotation.rs. A reference check only: never run by cargo test.
Usage: python3 scripts/beam3_planar_model.py
"""
import math
import numpy as np

EA, EJ, DL, MZ = 1e4, 1.0, 0.25, 1.5
RHO = 0.6
XI = (-1 / math.sqrt(3), 1 / math.sqrt(3))
ELEMENTS = ((0, 1, 2), (2, 3, 4))


def shape(x):
    return np.array([0.5 * x * (x - 1), 1 - x * x, 0.5 * x * (x + 1)])


def shape_derivative(x):
    return np.array([x - 0.5, -2 * x, x + 0.5]) / DL  # ds/dxi = DL


def gibbs(angle):
    return 2 * np.tan(np.asarray(angle) / 2)


def angle(g):
    return 2 * np.arctan(np.asarray(g) / 2)


def metric(g):
    """Planar G(g): d(angle)/dg."""
    return 1 / (1 + g * g / 4)


def rot(a):
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


def sections(phi, step):
    """(angle, curvature) of each element's two sections."""
    out = []
    for e, idx in enumerate(ELEMENTS):
        idx = list(idx)
        row = []
        for s in range(2):
            n, nd = shape(XI[s]), shape_derivative(XI[s])
            if step is None:
                g = gibbs(phi[idx] - phi[idx[1]])
                a, ap = n @ g, nd @ g
                row.append((phi[idx[1]] + angle(a), ap * metric(a)))
            else:
                phi_prev, g_ref, history = step
                g = gibbs(phi[idx] - phi_prev[idx] - angle(g_ref[idx]))
                a, ap, b, bp = n @ g_ref[idx], nd @ g_ref[idx], n @ g, nd @ g
                p0, k0 = history[e][s]
                row.append((p0 + angle(a) + angle(b), k0 + ap * metric(a) + bp * metric(b)))
        out.append(row)
    return out


def unpack(q):
    x = np.zeros((5, 2))
    x[1:] = q[:8].reshape(4, 2) + np.array([[DL * i, 0] for i in range(1, 5)])
    return x, np.concatenate([[0.0], q[8:]])


def residual(q, couple, step):
    x, phi = unpack(q)
    secs = sections(phi, step)
    f = np.zeros((5, 3))
    for e, idx in enumerate(ELEMENTS):
        idx = list(idx)
        for s in range(2):
            n, nd = shape(XI[s]), shape_derivative(XI[s])
            p, pp = n @ x[idx], nd @ x[idx]
            a, k = secs[e][s]
            r = rot(a)
            force = r @ (EA * (r.T @ pp - np.array([1.0, 0.0])))
            for node, sign in ((idx[s], 1), (idx[s + 1], -1)):
                arm = p - x[node]
                f[node, :2] += sign * force
                f[node, 2] += sign * (EJ * k + arm[0] * force[1] - arm[1] * force[0])
    f[4, 2] += couple
    return np.concatenate([f[1:, :2].ravel(), f[1:, 2]]), secs, phi


def newton(q, couple, step):
    for _ in range(60):
        r = residual(q, couple, step)[0]
        jac = np.zeros((12, 12))
        for j in range(12):
            dq = q.copy()
            dq[j] += 1e-7
            jac[:, j] = (residual(dq, couple, step)[0] - r) / 1e-7
        dx = np.linalg.solve(jac, -r)
        q = q + dx
        if np.linalg.norm(dx) < 1e-15:
            break
    return q


def ms_coefficients(h):
    den = 4 - (1 - RHO) ** 2
    beta = (3 * (1 - RHO) ** 2 + 4 * (2 * RHO - 1)) / den
    delta = (1 - RHO) ** 2 / (2 * den)
    return beta, h * (delta + 0.5), h * (beta / 2 + 0.5 - 2 * delta), h * (beta / 2 + delta)


def run(steps, incremental):
    h = 1 / steps
    q = np.zeros(12)
    history = [[(0.0, 0.0)] * 2 for _ in ELEMENTS]
    phis, omegas = [np.zeros(5)], [np.zeros(5)]
    for k in range(1, steps + 1):
        step = None
        if incremental:
            if k == 1:  # first step: constant predictor, trapezoidal coefficients
                b0 = h / 2
                gp_ref = omegas[-1]
                g_ref = b0 * gp_ref + h / 2 * omegas[-1]
            else:  # cubic Hermite predictor on g (g_{k-1} = 0, g_{k-2} = g_back)
                beta, b0, b1, b2 = ms_coefficients(h)
                g_back = gibbs(phis[-2] - phis[-1])
                u1, u2 = omegas[-1], omegas[-2] / metric(g_back)
                gp_ref = 12 / h * g_back + 8 * u1 + 5 * u2
                g_ref = beta * g_back + b0 * gp_ref + b1 * u1 + b2 * u2
            g_ref[0] = 0.0
            step = (phis[-1].copy(), g_ref, history)
        q = newton(q, MZ * k / steps, step)
        _, secs, phi = residual(q, MZ * k / steps, step)
        if incremental:
            g = gibbs(phi - phis[-1] - angle(g_ref))
            omega = metric(g) * g / b0 + metric(g_ref) * gp_ref
            omega[0] = 0.0
            history = secs
            phis.append(phi)
            omegas.append(omega)
    return q[6] + 4 * DL, q[7]


if __name__ == "__main__":
    for incremental, name in ((False, "romdyn"), (True, "MBDyn")):
        for steps in (1, 10, 100):
            x, y = run(steps, incremental)
            print(f"{name:6s} {steps:3d} load steps: tip x {x:.17e} y {y:.17e} m")
