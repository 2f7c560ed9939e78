# SPDX-License-Identifier: BSD-3-Clause
"""Loads the trainers' own code from copies outside the repository, for the tests that
run the logger against it (never committed here; Scripts/test-upstream-trainers.sh).

* gsplat: VIS4GS_GSPLAT_SRC is a gsplat source tree (the repository's root, holding
  gsplat/strategy/). Its strategy modules (base, default, mcmc, ops), utils.py and
  relocation.py are imported as they are, as the package ``gsplat``. Only what exists for
  CUDA alone is replaced: the compiled extension (``gsplat.cuda._wrapper`` /
  ``gsplat.cuda._backend``) is a stub whose "relocation" kernel is the double-loop torch
  reference of gsplat's own tests/test_relocation.py (v1.5.x has none: the kernel's formula,
  _relocation_formula), ``gsplat.quat_scale_to_covar_preci`` is gsplat's torch
  implementation (gsplat/cuda/_math.py on main, _torch_impl.py in v1.5.x), and
  GSPLAT_MCMC_BACKEND=torch selects gsplat's own torch path of inject_noise_to_position
  (v1.5.x's is torch only).
* original 3DGS: VIS4GS_3DGS_SRC is a folder holding the repository's
  scene/gaussian_model.py and utils/general_utils.py. The model is loaded with its
  explicit CUDA device redirected to the CPU (the text ``device="cuda"`` /
  ``device='cuda'`` / ``.cuda()``, nothing else) and stubs of the modules it imports but
  the densification does not use (simple_knn, plyfile, utils.sh_utils, ...).
"""

import importlib
import importlib.util
import os
import sys
import types

GSPLAT_ENV = "VIS4GS_GSPLAT_SRC"
GS3D_ENV = "VIS4GS_3DGS_SRC"

GSPLAT_HOW = (
    f"{GSPLAT_ENV} is not set: the tests against gsplat's own strategy code are skipped. "
    "Get a copy outside the repository (git clone https://github.com/nerfstudio-project/gsplat "
    "/path/gsplat; git -C /path/gsplat checkout 90d7b4b349e379ccf9ee6a8cef76aa40f48bb32e) and run "
    f"{GSPLAT_ENV}=/path/gsplat Scripts/test-upstream-trainers.sh")
GS3D_HOW = (
    f"{GS3D_ENV} is not set: the run against the original 3DGS GaussianModel is skipped. "
    "Put graphdeco-inria/gaussian-splatting's scene/gaussian_model.py and "
    "utils/general_utils.py into a folder outside the repository and run "
    f"{GS3D_ENV}=/path/folder Scripts/test-upstream-trainers.sh")


def _required(env, how):
    path = os.environ.get(env)
    if not path:
        if os.environ.get("VIS4GS_REQUIRE_UPSTREAM") == "1":  # the script: never vacuous
            raise RuntimeError(how)
        import pytest

        pytest.skip(how, allow_module_level=True)
    return path


def _module(name, **attrs):
    m = types.ModuleType(name)
    m.__dict__.update(attrs)
    sys.modules[name] = m
    return m


_gsplat = None


def gsplat_source():
    return os.path.abspath(_required(GSPLAT_ENV, GSPLAT_HOW))


def gsplat_commit(src):
    """The commit of the copy (COMMIT file written when exported, or git's HEAD)."""
    for candidate in (os.path.join(src, "COMMIT"),):
        if os.path.isfile(candidate):
            return open(candidate).read().strip()
    head = os.path.join(src, ".git", "HEAD")
    return open(head).read().strip() if os.path.isfile(head) else "unknown"


def load_gsplat():
    """Returns gsplat's strategy package (gsplat.strategy) loaded from the copy."""
    global _gsplat
    if _gsplat is not None:
        return _gsplat
    src = gsplat_source()
    pkg = os.path.join(src, "gsplat")
    if not os.path.isfile(os.path.join(pkg, "strategy", "ops.py")):
        raise RuntimeError(f"{GSPLAT_ENV}={src}: no gsplat/strategy/ops.py there")
    os.environ["GSPLAT_MCMC_BACKEND"] = "torch"  # gsplat's own switch to its torch path
    for name in [m for m in sys.modules if m == "gsplat" or m.startswith("gsplat.")]:
        del sys.modules[name]
    top = _module("gsplat", __path__=[pkg], __file__=os.path.join(pkg, "__init__.py"))
    kernels = {}

    def make_lazy_cuda_func(name):
        if name not in kernels:
            raise RuntimeError(f"gsplat's CUDA op {name!r} has no CPU replacement in the tests")
        return kernels[name]

    _module("gsplat.cuda", __path__=[os.path.join(pkg, "cuda")])
    _module("gsplat.cuda._wrapper", _make_lazy_cuda_func=make_lazy_cuda_func)
    _module("gsplat.cuda._backend", _C=None)
    # gsplat's torch implementation: gsplat/cuda/_math.py on main, _torch_impl.py in v1.5.x.
    for name in ("gsplat.cuda._math", "gsplat.cuda._torch_impl"):
        if os.path.isfile(os.path.join(pkg, "cuda", name.rsplit(".", 1)[1] + ".py")):
            top.quat_scale_to_covar_preci = importlib.import_module(name)._quat_scale_to_covar_preci
            break
    else:
        raise RuntimeError(f"{GSPLAT_ENV}={src}: neither gsplat/cuda/_math.py nor "
                           "gsplat/cuda/_torch_impl.py holds _quat_scale_to_covar_preci")
    importlib.import_module("gsplat.utils")
    importlib.import_module("gsplat.relocation")
    strategy = importlib.import_module("gsplat.strategy")

    # The relocation kernel: gsplat's torch reference from its own relocation test, or (v1.5.x
    # has no such test) the kernel's formula written out below. v1.5.x calls the kernel
    # without min_opacity and clamps nothing.
    test_file = os.path.join(src, "tests", "test_relocation.py")
    if os.path.isfile(test_file):
        spec = importlib.util.spec_from_file_location("gsplat_upstream_test_relocation", test_file)
        reference = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(reference)
        formula = reference._reference_relocation
    else:
        formula = _relocation_formula

    def relocation(opacities, scales, ratios, binoms, n_max, min_opacity=None):
        if min_opacity is None:
            return _relocation_formula(opacities, scales, ratios, binoms, None)
        return formula(opacities, scales, ratios, binoms, min_opacity)

    kernels["relocation"] = relocation
    strategy.commit = gsplat_commit(src)
    _gsplat = strategy
    return strategy


def _relocation_formula(opacities, scales, ratios, binoms, min_opacity):
    """MCMC relocation (Kheradmand et al. 2024, eq. 9), as gsplat's relocation kernel
    computes it: o' = 1 - (1 - o)^(1/n), s' = s * o / sum_{i=1..n} sum_{k<i} C(i-1, k)
    (-1)^k o'^(k+1) / sqrt(k+1); o' clamped to [min_opacity, 1 - eps] when given."""
    import math

    import torch

    out_o = torch.empty_like(opacities)
    out_s = torch.empty_like(scales)
    eps = torch.finfo(opacities.dtype).eps
    for idx in range(opacities.shape[0]):
        n = int(ratios[idx])
        o = float(opacities[idx])
        new_o = 1.0 - (1.0 - o) ** (1.0 / n)
        if min_opacity is not None:
            new_o = min(max(new_o, min_opacity), 1.0 - eps)
        total = sum(float(binoms[i - 1, k]) * (-1.0) ** k * new_o ** (k + 1) / math.sqrt(k + 1)
                    for i in range(1, n + 1) for k in range(i))
        out_o[idx] = new_o
        out_s[idx] = scales[idx] * (o / total)
    return out_o, out_s


def gs3d_source():
    return os.path.abspath(_required(GS3D_ENV, GS3D_HOW))


def load_3dgs_model():
    """Returns the original GaussianModel class, loaded from the copy on the CPU, and the
    number of device redirections made."""
    src = gs3d_source()
    for part in ("scene/gaussian_model.py", "utils/general_utils.py"):
        if not os.path.isfile(os.path.join(src, part)):
            raise RuntimeError(f"{GS3D_ENV}={src}: no {part} there")

    def load(name, path):
        text = open(path).read()
        redirected = 0
        for cuda, cpu in (('device="cuda"', 'device="cpu"'), ("device='cuda'", "device='cpu'"),
                          (".cuda()", ".cpu()")):
            redirected += text.count(cuda)
            text = text.replace(cuda, cpu)
        m = types.ModuleType(name)
        m.__file__ = path
        sys.modules[name] = m
        exec(compile(text, path, "exec"), m.__dict__)
        return m, redirected

    _module("utils", __path__=[])
    general, n1 = load("utils.general_utils", os.path.join(src, "utils", "general_utils.py"))
    sys.modules["utils"].general_utils = general
    # Imported by gaussian_model.py but used only by the PLY I/O and the point-cloud
    # initialisation, which the run replaces by its own initial model.
    _module("utils.system_utils", mkdir_p=lambda path: os.makedirs(path, exist_ok=True))
    _module("utils.sh_utils", RGB2SH=lambda rgb: (rgb - 0.5) / 0.28209479177387814)
    _module("utils.graphics_utils", BasicPointCloud=object)
    _module("plyfile", PlyData=None, PlyElement=None)
    _module("simple_knn", __path__=[])
    _module("simple_knn._C", distCUDA2=None)
    model, n2 = load("scene.gaussian_model", os.path.join(src, "scene", "gaussian_model.py"))
    commit = "unknown"
    if os.path.isfile(os.path.join(src, "COMMIT")):
        commit = open(os.path.join(src, "COMMIT")).read().strip()
    model.GaussianModel.commit = commit
    return model.GaussianModel, n1 + n2


def readme_fragments(title):
    """The README's integration block under the heading ``title``, cut at its comment
    lines: {comment: code}. The upstream tests execute these fragments in the trainers'
    loops, so the README shows exactly what was run."""
    readme = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                          "README.md")
    text = open(readme).read()
    section = text[text.index(title):]
    block = section[section.index("```python\n") + 10:]
    block = block[:block.index("```")]
    fragments, key, lines = {}, "", []
    for line in block.splitlines():
        if line.startswith("# "):
            fragments[key] = "\n".join(lines)
            key, lines = line[2:].strip(), []
        else:
            lines.append(line)
    fragments[key] = "\n".join(lines)
    return fragments
