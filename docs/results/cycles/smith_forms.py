#!/usr/bin/python3
"""What the two Smith masking forms alone make of a white GGX metal sphere (F = 1 whatever the
angle, so no Fresnel form enters): the directional albedo of the GGX lobe with glTF's
height-correlated G2 = 1 / (1 + Lambda(v) + Lambda(l)) and with the separable G1(v) G1(l) of
Cycles 3.4's Glossy BSDF (bsdf_microfacet.h: G = G1o * G1i), by quadrature over l, averaged over a
sphere's pixels seen from afar (n.v has the density 2 n.v over the disc). Light from the other
spheres is not in it.

    /usr/bin/python3 docs/results/cycles/smith_forms.py
"""
import numpy as np


def albedo(alpha, mu, correlated, n=300):
    th = (np.arange(n) + 0.5) / n * (np.pi / 2)
    ph = (np.arange(2 * n) + 0.5) / (2 * n) * 2 * np.pi
    T, P = np.meshgrid(th, ph, indexing="ij")
    l = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1)
    v = np.array([np.sqrt(1 - mu * mu), 0.0, mu])
    h = l + v
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    nh, nl, a2 = h[..., 2], l[..., 2], alpha * alpha
    D = a2 / (np.pi * (nh * nh * (a2 - 1) + 1) ** 2)

    def lam(c):
        return (-1 + np.sqrt(1 + a2 * (1 - c * c) / (c * c))) / 2

    G = 1 / (1 + lam(mu) + lam(nl)) if correlated else 1 / ((1 + lam(mu)) * (1 + lam(nl)))
    f_cos = D * G / (4 * mu)  # D G / (4 n.v n.l) x n.l
    dw = np.sin(T) * (np.pi / 2 / n) * (2 * np.pi / (2 * n))
    return float((f_cos * dw).sum())


def main():
    mus = (np.arange(64) + 0.5) / 64
    weights = 2 * mus / (2 * mus).sum()
    for roughness in (1.0, 0.5, 0.3):
        alpha = roughness * roughness
        hc = sum(w * albedo(alpha, m, True) for m, w in zip(mus, weights))
        sp = sum(w * albedo(alpha, m, False) for m, w in zip(mus, weights))
        print(f"roughness {roughness}: sphere-averaged albedo, height-correlated {hc:.4f}, "
              f"separable {sp:.4f}, ratio {hc / sp:.4f}")


if __name__ == "__main__":
    main()
