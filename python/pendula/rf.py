"""rf drive as the experiment gives it: a current, a voltage behind a source impedance, or a power in dBm.

:class:`pendula.Junction` takes the rf drive as a current amplitude I_rf
(I_rf cos(2π f t)).  :func:`rf_current` converts what a microwave source
states into that amplitude, with the formula stated.
"""

from __future__ import annotations

import math

from . import _checks

__all__ = ["rf_current"]


def rf_current(*, current: float | None = None, voltage: float | None = None,
               source_impedance: float | None = None, power_dbm: float | None = None,
               impedance: float | None = None) -> float:
    """The rf current amplitude I_rf (A) of a drive given as the laboratory states it.

    Exactly one of three forms:

    * ``current``: the amplitude itself, A.
    * ``voltage`` with ``source_impedance``: a voltage amplitude V_rf (V)
      behind a source impedance Z_s (ohm, real): I_rf = V_rf / Z_s.  The
      source is taken as stiff (Z_s much larger than the junction's
      resistance, a current bias), as on-chip bias resistors make it; the
      junction's own voltage is not subtracted.
    * ``power_dbm`` with ``impedance``: the power P = 1 mW · 10^(P_dBm / 10)
      of a sine delivered into the stated real impedance Z (a 50 ohm line):
      P = I_rf² Z / 2, so I_rf = sqrt(2 P / Z).  A power without an
      impedance has no current: refused.

    The attenuation of the lines between the source and the sample is the
    user's to subtract from ``power_dbm`` first.

    Parameters
    ----------
    current : float, optional
        I_rf, A (>= 0).
    voltage, source_impedance : float, optional
        V_rf (V, >= 0) and Z_s (ohm, > 0), both or neither.
    power_dbm, impedance : float, optional
        The power, dBm (finite), and Z (ohm, > 0), both or neither.

    Returns
    -------
    float
        I_rf, A.

    Raises
    ------
    TypeError
        No form or more than one, or a value that is not a real number.
    ValueError
        A power without an impedance, a voltage without a source impedance
        (or either impedance without its quantity), or a value out of range,
        naming the parameter.

    See Also
    --------
    pendula.Junction.iv_curve : takes the rf current it gives.

    Examples
    --------
    >>> from pendula.rf import rf_current
    >>> round(rf_current(power_dbm=0.0, impedance=50.0) * 1e3, 6)       # mA: sqrt(2 mW / 50 ohm)
    6.324555
    >>> rf_current(voltage=1e-3, source_impedance=1e3)                  # A
    1e-06
    """
    given = [name for name, v in (("current", current), ("voltage", voltage), ("power_dbm", power_dbm))
             if v is not None]
    if power_dbm is None and impedance is not None:
        raise ValueError("parameter 'impedance' is given without 'power_dbm' (the impedance is the one the "
                         "power is stated at)")
    if voltage is None and source_impedance is not None:
        raise ValueError("parameter 'source_impedance' is given without 'voltage'")
    if len(given) != 1:
        raise TypeError("give the rf drive as exactly one of current=, voltage= (with source_impedance=) or "
                        f"power_dbm= (with impedance=); got {given or 'none'}")
    if current is not None:
        return _checks.real(current, "parameter 'current'", 0.0)
    if voltage is not None:
        v = _checks.real(voltage, "parameter 'voltage'", 0.0)
        if source_impedance is None:
            raise ValueError("parameter 'source_impedance' is needed with 'voltage': a voltage drives a current "
                             "only through an impedance (I_rf = V_rf / Z_s)")
        return v / _checks.real(source_impedance, "parameter 'source_impedance'", 0.0, lo_open=True)
    p = _checks.real(power_dbm, "parameter 'power_dbm'")
    if impedance is None:
        raise ValueError("parameter 'impedance' is needed with 'power_dbm': a power gives a current only at a "
                         "stated impedance (I_rf = sqrt(2 P / Z); 50 ohm for a coaxial line)")
    z = _checks.real(impedance, "parameter 'impedance'", 0.0, lo_open=True)
    return math.sqrt(2.0 * 1e-3 * 10.0 ** (p / 10.0) / z)
