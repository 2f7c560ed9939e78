"""An independent float64 reference of the 3DGS forward pass, in numpy.

Written from /work/shared/reference/3dgs-reference.md §1.1 and §2 (the graphdeco-inria
rasteriser: EWA projection with the 0.3 low-pass dilation, the 3-sigma radius and 16x16 tile
rectangle that decide which pixels evaluate a Gaussian, SH degree 0-3 colour + 0.5 clamped at
0, depth order of the view-space z, alpha = min(0.99, o exp(power)), alpha < 1/255 skipped,
stop before T drops below 1e-4, background), never from Vis4GS's C++. The files are parsed
here too (INRIA PLY by property name, antimatter15 .splat), so nothing of Vis4GS stands
between a file and this image.

Special values follow the reference's arithmetic (Documentation/special-values.md):
sigmoid(+inf) = 1 and sigmoid(-inf) = 0, exp(-inf) = 0 scale (a dilated point or disk), a
zero quaternion normalised by max(|q|, 1e-12) stays 0 and its rotation matrix is the
identity. Values the reference has no answer for (NaN, infinite positions, rotations or
+inf log-scales, non-finite SH) are left out, as Vis4GS documents.

The compositing loop runs over the Gaussians in depth order and is vectorised over the
pixels of each Gaussian's tile rectangle (cropped to the bounding box of its alpha >= 1/255
ellipse, outside which the reference skips every pixel anyway), so a scene of ~10^4-10^5 Gaussians at 160x120 to
320x240 renders in seconds.
"""
import numpy as np

C0 = 0.28209479177387814
C1 = 0.4886025119029199
C2 = (1.0925484305920792, -1.0925484305920792, 0.31539156525252005, -1.0925484305920792,
      0.5462742152960396)
C3 = (-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154,
      -0.4570457994644658, 1.445305721320277, -0.5900435899266435)


class Scene:
    """Raw parameters as a trainer stores them (float64 copies of the file's values):
    means [N,3], log_scales [N,3] (or None), scales [N,3] linear (or None), rotations [N,4]
    w,x,y,z unnormalised, opacities [N] activated, sh [N,K,3] coefficient-major (or None),
    colors [N,3] view-independent colour (instead of SH, for .splat)."""

    def __init__(self, means, rotations, opacities, log_scales=None, scales=None, sh=None,
                 colors=None):
        self.means = means
        self.rotations = rotations
        self.opacities = opacities
        self.scales = np.exp(log_scales) if scales is None else scales
        self.sh = sh
        self.colors = colors


def sigmoid(x):
    with np.errstate(over="ignore"):
        return 1.0 / (1.0 + np.exp(-x))


def read_ply_vertices(path):
    """The vertex element of a binary little-endian PLY whose properties are all float32,
    as a dict name -> float64 array (what the INRIA trainer and its variants write)."""
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline()
            if not line:
                raise ValueError(f"{path}: no end_header")
            line = line.decode("ascii").strip()
            header.append(line)
            if line == "end_header":
                break
        body = f.read()
    if "format binary_little_endian 1.0" not in header:
        raise ValueError(f"{path}: not a binary little-endian PLY")
    count, names, in_vertex = 0, [], False
    for line in header:
        words = line.split()
        if words[:1] == ["element"]:
            in_vertex = words[1] == "vertex"
            if in_vertex:
                count = int(words[2])
        elif words[:1] == ["property"] and in_vertex:
            if words[1] not in ("float", "float32"):
                raise ValueError(f"{path}: property {words[-1]} is {words[1]}, not float")
            names.append(words[2])
    rows = np.frombuffer(body, dtype="<f4", count=count * len(names)).reshape(count, len(names))
    return {name: rows[:, k].astype(np.float64) for k, name in enumerate(names)}


def read_inria_ply(path):
    """An INRIA 3DGS point_cloud.ply (reference §1.1): f_rest is channel-major in the file."""
    v = read_ply_vertices(path)
    rest = sorted((n for n in v if n.startswith("f_rest_")), key=lambda n: int(n[7:]))
    k = len(rest) // 3 + 1
    dc = np.stack([v[f"f_dc_{c}"] for c in range(3)], 1)[:, None, :]
    if rest:
        r = np.stack([v[n] for n in rest], 1).reshape(-1, 3, k - 1).transpose(0, 2, 1)
        sh = np.concatenate([dc, r], 1)
    else:
        sh = dc
    return Scene(means=np.stack([v["x"], v["y"], v["z"]], 1),
                 log_scales=np.stack([v[f"scale_{i}"] for i in range(3)], 1),
                 rotations=np.stack([v[f"rot_{i}"] for i in range(4)], 1),
                 opacities=sigmoid(v["opacity"]), sh=sh)


def write_inria_ply(path, means, log_scales, rotations, logits, sh):
    """Writes an INRIA PLY (x y z nx ny nz f_dc f_rest opacity scale rot, float32)."""
    n, k = sh.shape[0], sh.shape[1]
    rest = sh[:, 1:, :].transpose(0, 2, 1).reshape(n, -1)
    cols = [means, np.zeros((n, 3)), sh[:, 0, :], rest, logits[:, None], log_scales, rotations]
    names = (["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"] +
             [f"f_rest_{j}" for j in range(3 * (k - 1))] +
             ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"])
    data = np.concatenate(cols, 1).astype("<f4")
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {n}"]
    header += [f"property float {name}" for name in names] + ["end_header"]
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n").encode("ascii"))
        f.write(data.tobytes())


def read_splat(path):
    """An antimatter15 .splat: 32 bytes per Gaussian: position (3 f32), linear scale (3 f32),
    RGBA (4 u8: the view-independent colour and the opacity, each /255), quaternion w,x,y,z
    (4 u8, (b - 128) / 128)."""
    raw = np.fromfile(path, dtype=np.uint8)
    if raw.size % 32:
        raise ValueError(f"{path}: size is not a multiple of 32")
    rows = raw.reshape(-1, 32)
    floats = rows[:, :24].copy().view("<f4").astype(np.float64)
    rgba = rows[:, 24:28].astype(np.float64) / 255.0
    quat = (rows[:, 28:32].astype(np.float64) - 128.0) / 128.0
    return Scene(means=floats[:, :3], scales=floats[:, 3:6], rotations=quat,
                 opacities=rgba[:, 3], colors=rgba[:, :3])


def rotation_matrices(q):
    n = np.linalg.norm(q, axis=1, keepdims=True)
    q = q / np.maximum(n, 1e-12)
    w, x, y, z = q.T
    return np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                     2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                     2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
                    1).reshape(-1, 3, 3)


def sh_basis(d, degree):
    """Y_k(d) for k < (degree+1)^2, reference §2.4 table; d [N,3] unit directions."""
    x, y, z = d.T
    out = [np.full_like(x, C0)]
    if degree >= 1:
        out += [-C1 * y, C1 * z, -C1 * x]
    if degree >= 2:
        xx, yy, zz = x * x, y * y, z * z
        out += [C2[0] * x * y, C2[1] * y * z, C2[2] * (2 * zz - xx - yy), C2[3] * x * z,
                C2[4] * (xx - yy)]
    if degree >= 3:
        out += [C3[0] * y * (3 * xx - yy), C3[1] * x * y * z, C3[2] * y * (4 * zz - xx - yy),
                C3[3] * z * (2 * zz - 3 * xx - 3 * yy), C3[4] * x * (4 * zz - xx - yy),
                C3[5] * z * (xx - yy), C3[6] * x * (xx - 3 * yy)]
    return np.stack(out, 1)


def answerable(scene):
    """Gaussians the reference computation has an answer for (special-values.md)."""
    ok = np.isfinite(scene.means).all(1) & np.isfinite(scene.rotations).all(1)
    ok &= np.isfinite(scene.scales).all(1) & ~np.isnan(scene.opacities)
    if scene.sh is not None:
        ok &= np.isfinite(scene.sh.reshape(len(ok), -1)).all(1)
    if scene.colors is not None:
        ok &= np.isfinite(scene.colors).all(1)
    return ok


def render(scene, world_to_camera, width, height, fx, fy, background=(0.0, 0.0, 0.0),
           sh_degree=None):
    """Renders @p scene: returns (rgb [H,W,3] not clamped, transmittance [H,W]). Row 0 is the
    top of the camera image; the principal point is the image centre (the reference's)."""
    W, H = int(width), int(height)
    Rv = np.asarray(world_to_camera, dtype=np.float64).reshape(4, 4)[:3, :3]
    tv = np.asarray(world_to_camera, dtype=np.float64).reshape(4, 4)[:3, 3]
    keep = answerable(scene)
    idx = np.nonzero(keep)[0]
    mu = scene.means[idx]
    t = mu @ Rv.T + tv
    front = t[:, 2] > 0.2
    idx, mu, t = idx[front], mu[front], t[front]

    # Full projection F = P W2C (reference §2.2), znear 0.01, zfar 100.
    tan_x, tan_y = W / (2.0 * fx), H / (2.0 * fy)
    hx = t[:, 0] / tan_x
    hy = t[:, 1] / tan_y
    hw = t[:, 2]
    u = ((hx / (hw + 1e-7) + 1.0) * W - 1.0) / 2.0
    v = ((hy / (hw + 1e-7) + 1.0) * H - 1.0) / 2.0

    R = rotation_matrices(scene.rotations[idx])
    s2 = scene.scales[idx] ** 2
    sigma = np.einsum("nik,nk,njk->nij", R, s2, R)
    limx, limy = 1.3 * tan_x, 1.3 * tan_y
    tz = t[:, 2]
    txc = np.clip(t[:, 0] / tz, -limx, limx) * tz
    tyc = np.clip(t[:, 1] / tz, -limy, limy) * tz
    J = np.zeros((len(tz), 2, 3))
    J[:, 0, 0] = fx / tz
    J[:, 0, 2] = -fx * txc / (tz * tz)
    J[:, 1, 1] = fy / tz
    J[:, 1, 2] = -fy * tyc / (tz * tz)
    M = J @ Rv
    cov = np.einsum("nia,nab,njb->nij", M, sigma, M)
    a = cov[:, 0, 0] + 0.3
    b = cov[:, 0, 1]
    c = cov[:, 1, 1] + 0.3
    det = a * c - b * b
    nz = det != 0
    A, B, Cc = c / np.where(nz, det, 1), -b / np.where(nz, det, 1), a / np.where(nz, det, 1)
    mid = 0.5 * (a + c)
    root = np.sqrt(np.maximum(0.1, mid * mid - det))
    radius = np.ceil(3.0 * np.sqrt(np.maximum(mid + root, mid - root)))
    gx, gy = (W + 15) // 16, (H + 15) // 16
    x0 = np.clip(np.trunc((u - radius) / 16), 0, gx).astype(np.int64)
    x1 = np.clip(np.trunc((u + radius + 15) / 16), 0, gx).astype(np.int64)
    y0 = np.clip(np.trunc((v - radius) / 16), 0, gy).astype(np.int64)
    y1 = np.clip(np.trunc((v + radius + 15) / 16), 0, gy).astype(np.int64)
    visible = nz & ((x1 - x0) * (y1 - y0) > 0)

    # Colour (reference §2.4): direction from the camera centre to the mean.
    if scene.sh is not None:
        k = scene.sh.shape[1]
        degree = int(round(np.sqrt(k))) - 1
        if sh_degree is not None:
            degree = min(degree, sh_degree)
        campos = -Rv.T @ tv
        d = mu - campos
        d = d / np.linalg.norm(d, axis=1, keepdims=True)
        basis = sh_basis(d, degree)
        colour = np.einsum("nk,nkc->nc", basis, scene.sh[idx, :basis.shape[1], :]) + 0.5
        colour = np.maximum(colour, 0.0)
    else:
        colour = scene.colors[idx]
    opacity = scene.opacities[idx]
    # A Gaussian with o < 1/255 never reaches alpha >= 1/255: leaving it out changes nothing.
    visible &= opacity >= 1.0 / 255.0

    order = np.argsort(tz, kind="stable")
    order = order[visible[order]]
    # Pixels outside the ellipse o exp(power) >= 1/255 are skipped by the reference anyway, so
    # the loop only visits the tile rectangle's part of that ellipse's bounding box (plus a
    # pixel of margin): |dx| <= sqrt(2 ln(255 o) a), |dy| <= sqrt(2 ln(255 o) c).
    with np.errstate(divide="ignore"):
        reach = 2.0 * np.log(np.maximum(255.0 * opacity, 1.0))
    ex = np.sqrt(reach * np.maximum(a, 0)) + 1.0
    ey = np.sqrt(reach * np.maximum(c, 0)) + 1.0
    bx0 = np.maximum(16 * x0, np.floor(u - ex)).astype(np.int64)
    bx1 = np.minimum(np.minimum(16 * x1, W), np.ceil(u + ex) + 1).astype(np.int64)
    by0 = np.maximum(16 * y0, np.floor(v - ey)).astype(np.int64)
    by1 = np.minimum(np.minimum(16 * y1, H), np.ceil(v + ey) + 1).astype(np.int64)

    rgb = np.zeros((H, W, 3))
    T = np.ones((H, W))
    done = np.zeros((H, W), dtype=bool)
    xs = np.arange(W, dtype=np.float64)
    ys = np.arange(H, dtype=np.float64)
    for i in order:
        px0, px1, py0, py1 = bx0[i], bx1[i], by0[i], by1[i]
        if px0 >= px1 or py0 >= py1:
            continue
        sub_done = done[py0:py1, px0:px1]
        dx = u[i] - xs[px0:px1]
        dy = (v[i] - ys[py0:py1])[:, None]
        power = -0.5 * (A[i] * dx * dx + Cc[i] * dy * dy) - B[i] * dy * dx
        alpha = np.minimum(0.99, opacity[i] * np.exp(np.minimum(power, 0.0)))
        use = (power <= 0) & (alpha >= 1.0 / 255.0) & ~sub_done
        if not use.any():
            continue
        sub_T = T[py0:py1, px0:px1]
        t_next = sub_T * (1.0 - alpha)
        stop = use & (t_next < 1e-4)
        sub_done |= stop
        blend = use & ~stop
        weight = np.where(blend, alpha * sub_T, 0.0)
        rgb[py0:py1, px0:px1] += weight[:, :, None] * colour[i]
        sub_T[blend] = t_next[blend]
    rgb += T[:, :, None] * np.asarray(background, dtype=np.float64)
    return rgb, T


def look_at(eye, target, up=(0.0, 0.0, 1.0)):
    """World-to-camera 4x4 in the reference's axes (x right, y down, z forward)."""
    eye, target, up = (np.asarray(p, dtype=np.float64) for p in (eye, target, up))
    z = target - eye
    z /= np.linalg.norm(z)
    if abs(np.dot(z, up)) > 0.99 * np.linalg.norm(up):
        up = np.array([0.0, 1.0, 0.0]) if abs(z[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    y = -(up - np.dot(up, z) * z)
    y /= np.linalg.norm(y)
    x = np.cross(y, z)
    m = np.eye(4)
    m[:3, :3] = np.stack([x, y, z])
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def orbit_cameras(means, count=3, distance=2.0, inside=True):
    """Cameras around a scene: @p count on an orbit around the robust bounds (5-95th
    percentiles of the means) at @p distance times their half-diagonal, at varied
    elevations, and (if @p inside) one inside the bounds, near the centre, looking at it from
    close by (the near-plane cull and Gaussians larger than the view)."""
    finite = means[np.isfinite(means).all(1)]
    lo, hi = np.percentile(finite, 5, axis=0), np.percentile(finite, 95, axis=0)
    centre = 0.5 * (lo + hi)
    half = 0.5 * np.linalg.norm(hi - lo)
    cams = []
    for j in range(count):
        azimuth = 2 * np.pi * (j + 0.17) / count
        elevation = (-0.35, 0.2, 0.6, -0.1)[j % 4]
        eye = centre + distance * half * np.array([np.cos(azimuth) * np.cos(elevation),
                                                   np.sin(azimuth) * np.cos(elevation),
                                                   np.sin(elevation)])
        cams.append(look_at(eye, centre))
    if inside:
        cams.append(look_at(centre + np.array([0.25, -0.15, 0.1]) * (hi - lo), centre))
    return cams


def psnr(a, b):
    mse = float(np.mean((np.asarray(a, np.float64) - np.asarray(b, np.float64)) ** 2))
    return float("inf") if mse == 0 else 10.0 * np.log10(1.0 / mse)
