"""The scene files of the systems built by their own class (groups &double, &foucault, &network) as
Python objects: the system and the keyword arguments of its ``simulate``.  The text is read and checked
by the kernel's reader of each system (kernel/dispatch/pendula_*_scene.f90), the one pendula-run uses:
no second parser here, and every refusal is pendula-run's message naming the field.
"""

from __future__ import annotations

import os
import tempfile
from typing import Any

import numpy as np

from .. import _kernel

#: the most elements a network's scene file names (kernel/dispatch/pendula_network_scene.f90)
_MAX_ELEMENTS = 1000
_PER_ELEMENT = ("mass", "damping", "eps", "bias", "drive_amplitude", "drive_frequency", "drive_phase")


def _text(b) -> str:
    return (b.decode("utf-8", errors="replace") if isinstance(b, bytes) else str(b)).strip()


def _read(path: bytes, source: str, group: str) -> tuple[Any, dict]:
    from ..scene import SceneError

    def fail(msg) -> SceneError:
        return SceneError(_text(msg).replace(os.fsdecode(path), source, 1))

    if group == "double":
        from .double_motion import DoublePendulum

        x, method, status, msg = _kernel.double_scene_fields_v(path)
        if status:
            raise fail(msg)
        method, x = _text(method), x.tolist()
        system = DoublePendulum(m1=x[0], m2=x[1], l1=x[2], l2=x[3], g=x[4], rods=bool(x[5]), damping=x[6:8])
        run = dict(t=np.linspace(0.0, x[12], int(x[16])), theta1=x[8], theta2=x[9], omega1=x[10], omega2=x[11],
                   method=method, rtol=x[14], atol=x[15])
        if method != "dop853":
            run["dt"] = x[13]
        return system, run
    if group == "foucault":
        from .foucault import FoucaultPendulum

        x, status, msg = _kernel.foucault_scene_fields_v(path)
        if status:
            raise fail(msg)
        x = x.tolist()
        system = FoucaultPendulum(latitude=x[0], length=x[1], g=x[2], earth_rate=x[3], damping=x[4],
                                  anisotropy=(x[5], x[6]))
        run = dict(t=np.linspace(0.0, x[11], int(x[13])), theta0=x[7], azimuth=x[8], theta_dot0=x[9],
                   phi_dot0=x[10], rtol=x[12], atol=x[12] * x[1])
        return system, run
    from .network import Network

    n, x, per, topology, method, status, msg = _kernel.network_scene_fields_v(path, _MAX_ELEMENTS)
    if status:
        raise fail(msg)
    method, x = _text(method), x.tolist()
    per = per[:n]
    system = Network(int(n), topology=_text(topology), strength=x[0],
                     **{name: per[:, k].copy() for k, name in enumerate(_PER_ELEMENT)})
    run = dict(t=np.linspace(0.0, x[1], int(x[5])), phi0=per[:, 7].copy(), v0=per[:, 8].copy(), method=method,
               rtol=x[3], atol=x[4])
    if method != "dop853":
        run["dt"] = x[2]
    return system, run


def system_from_namelist(text: str, source: str = "<scene>") -> tuple[Any, dict]:
    """The system of a scene file's text and the keyword arguments of its run.

    Parameters
    ----------
    text : str
        One namelist group: ``&double``, ``&foucault`` or ``&network`` (the fields pendula-run reads;
        docs/source/scenes.rst).
    source : str
        The name that messages give the text (a file's path).

    Returns
    -------
    system : DoublePendulum or FoucaultPendulum or Network
        The system the group describes.
    run : dict
        The keyword arguments of ``system.simulate``: the output times ``t``, the start and the method
        with its tolerances, so that ``system.simulate(**run)`` is the run pendula-run makes of the file.

    Raises
    ------
    SceneError
        The text is not one of these groups, or a field is out of its domain or does not read: the
        message of pendula-run, naming the field.

    See Also
    --------
    DoublePendulum, FoucaultPendulum, Network : the systems, and their ``simulate``.
    Scene.from_namelist : the scene of the rigid, cord, cycloid and gravity models (group ``&scene``).

    Examples
    --------
    >>> import pendula
    >>> system, run = pendula.system_from_namelist("&double theta1 = 2.0, t_end = 1.0, n_samples = 3 /")
    >>> type(system).__name__, run["t"].tolist(), run["theta1"], run["method"]
    ('DoublePendulum', [0.0, 0.5, 1.0], 2.0, 'dop853')
    >>> float(system.simulate(**run)["theta1"][0])
    2.0
    """
    from ..scene import SceneError

    if not isinstance(text, str):
        raise TypeError(f"text: expected the namelist text as str, got {type(text).__name__}")
    with tempfile.TemporaryDirectory(prefix="pendula-scene-") as folder:
        path = os.path.join(folder, "scene.nml")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text if text.endswith("\n") else text + "\n")
        raw = os.fsencode(path)
        group, _, _, status, msg = _kernel.system_scene_size_v(raw)
        group = _text(group)
        if status == 1 or group not in ("double", "foucault", "network"):
            raise SceneError(f"{source}: the text must hold one group &double, &foucault or &network")
        if status:
            raise SceneError(_text(msg).replace(path, source, 1))
        return _read(raw, source, group)
