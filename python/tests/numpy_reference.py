"""The shading formula (docs/shading.md) in NumPy float64, written from the formula alone, to check
the kernel from Python (as the C++ reference in lab/reference does from C++)."""
import numpy as np

from accuracy_bound import ERROR_FLOOR


def _unit(v):
    length = np.linalg.norm(v, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(length > 0, v / length, 0.0)


def shade(scene, P, N, material):
    """RGBA float64 (H, W, 4) for G-buffer arrays P, N (H, W, 3) and material indices (H, W)."""
    P = P.astype(np.float64)
    N = N.astype(np.float64)
    shaded = (material >= 0) & np.isfinite(P).all(-1) & np.isfinite(N).all(-1) & np.isfinite(material)
    index = np.where(shaded, material, 0).astype(np.int64)
    table = lambda field: np.array([getattr(m, field) for m in scene.materials], dtype=np.float64)[index]
    ka, kd, ks = table("ka"), table("kd"), table("ks")
    q = np.array([m.shininess for m in scene.materials], dtype=np.float64)[index][..., None]

    n = _unit(N)
    v = _unit(np.array(scene.camera.eye) - P)
    total = ka * np.array(scene.ambient)
    for light in scene.lights:
        if light.type == "point":
            l = _unit(np.array(light.position) - P)
        else:
            l = np.broadcast_to(-_unit(np.array(light.direction)), P.shape)
        ndl = np.sum(n * l, axis=-1, keepdims=True)
        lit = ndl > 0
        r = 2 * ndl * n - l
        vr = np.maximum(np.sum(v * r, axis=-1, keepdims=True), 0.0)
        color = np.array(light.color)
        total = total + np.where(lit, kd * ndl * color + ks * np.power(vr, q) * color, 0.0)

    out = np.empty(P.shape[:2] + (4,))
    out[..., :3] = np.where(shaded[..., None], total, np.array(scene.background))
    out[..., 3] = shaded
    return out


def worst_relative_error(image, expected, shaded):
    """Max relative error over shaded pixels' RGB, |got - want| / max(|want|, ERROR_FLOOR) as the
    product's bound is measured (accuracy_bound.py), and where it is."""
    error = np.abs(image[..., :3] - expected[..., :3]) / np.maximum(np.abs(expected[..., :3]), ERROR_FLOOR)
    error = np.where(shaded[..., None], error, 0.0)
    worst = np.unravel_index(np.argmax(error), error.shape)
    return float(error[worst]), worst
