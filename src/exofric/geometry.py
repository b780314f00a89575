"""The friction structure's cross-section: hole, air tube and driving wire.

Placement (plane section, mm): the hole (diameter D) is centred at the origin.
The wire (diameter d2) lies against the hole wall at the top, centre
``(0, D/2 - d2/2)``; the tube (outer diameter d1) rests on the opposite side of
the wall, centre ``(0, -(D/2 - d1/2))``. The clearance ``D - d1 - d2`` is the
gap between tube and wire along the line of centres (the y axis).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import InputError, check_finite, check_positive

__all__ = ["Structure", "BASE", "check_size_mm"]


def check_size_mm(name: str, value: float, what: str = "") -> float:
    """Return ``float(value)`` if it is a physical size of a friction structure, else raise.

    Allowed: finite numbers in [``defaults.SIZE_MIN_MM``, ``defaults.SIZE_MAX_MM``] mm (10 um
    to 1 m: every hole, tube, wire and tube length of a worn exosuit lies inside).

    Parameters
    ----------
    name : str
        Parameter name used in the error message (``"hole_mm"``).
    value : float
        The size (mm).
    what : str
        What the size is, quoted in the message (``"hole diameter D"``).

    Returns
    -------
    float
        ``float(value)`` (mm).

    Raises
    ------
    InputError
        Not a number (strings, None...), not finite, or outside the range.

    Examples
    --------
    >>> check_size_mm("hole_mm", 10)
    10.0
    >>> check_size_mm("hole_mm", 1e300, "hole diameter D")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: hole_mm (hole diameter D) must be in [0.01, 1000] mm, got 1e+300
    """
    label = f"{name} ({what})" if what else name
    if isinstance(value, (str, bytes, bool)) or value is None:
        raise InputError(f"{label} must be a number in mm, got {value!r}", param=name)
    v = check_finite(label, value)
    lo, hi = defaults.SIZE_MIN_MM, defaults.SIZE_MAX_MM
    if not lo <= v <= hi:
        raise InputError(f"{label} must be in [{lo:g}, {hi:g}] mm, got {v:g}", param=name)
    return v


@checked_init
@dataclass(frozen=True)
class Structure:
    """A hole-tube-wire structure (all sizes in mm).

    Parameters
    ----------
    hole_mm : float
        Hole diameter D (rigid, aluminium).
    tube_od_mm : float
        Air tube outer diameter d1 (silicone).
    tube_id_mm : float
        Air tube inner diameter (not printed in the paper; see calibration).
    wire_mm : float
        Driving wire diameter d2 (rigid, steel).
    length_mm : float
        Tube length L over which forces per unit depth are integrated (paper: 116).
    name : str
        Optional label (e.g. ``"test 5"``).

    Examples
    --------
    >>> s = Structure(10.0, 8.3, 4.97, 1.6)
    >>> round(s.clearance_mm, 3)
    0.1
    """

    hole_mm: float
    tube_od_mm: float
    tube_id_mm: float
    wire_mm: float
    length_mm: float = 116.0
    name: str = ""

    def __post_init__(self) -> None:
        # Every size is a finite number in [SIZE_MIN_MM, SIZE_MAX_MM] (defaults.py says why:
        # a worn friction structure is between 10 um and 1 m; 1e300 mm would reach the solver
        # and fail there). Stored as float; strings ("10") are refused like any non-number.
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): sizes stored as float whatever
        # number type is given (ints, NumPy scalars: JSON-ready, one repr).
        for attr, what in (("hole_mm", "hole diameter D"), ("tube_od_mm", "tube outer diameter d1"),
                           ("tube_id_mm", "tube inner diameter"), ("wire_mm", "wire diameter d2"),
                           ("length_mm", "tube length L")):
            object.__setattr__(self, attr, check_size_mm(attr, getattr(self, attr), what))
        if not isinstance(self.name, str):
            raise InputError(f"name must be a string, got {self.name!r}")
        if self.tube_id_mm >= self.tube_od_mm:
            raise InputError(
                f"tube_id_mm must be < tube_od_mm ({self.tube_od_mm:g} mm), got {self.tube_id_mm:g}"
            )
        if self.tube_od_mm + self.wire_mm > self.hole_mm:
            raise InputError(
                f"tube and wire do not fit: tube_od_mm + wire_mm = "
                f"{self.tube_od_mm + self.wire_mm:g} mm must be <= hole_mm = {self.hole_mm:g} mm"
            )

    @property
    def clearance_mm(self) -> float:
        """Gap D - d1 - d2 between tube and wire before inflation (mm)."""
        return self.hole_mm - self.tube_od_mm - self.wire_mm

    @property
    def wall_mm(self) -> float:
        """Tube wall thickness (d1 - ID)/2 (mm)."""
        return 0.5 * (self.tube_od_mm - self.tube_id_mm)

    @property
    def tube_center_mm(self) -> tuple[float, float]:
        """Initial tube centre (x, y) in mm (touching the hole wall at the bottom)."""
        return (0.0, -(0.5 * self.hole_mm - 0.5 * self.tube_od_mm))

    @property
    def wire_center_mm(self) -> tuple[float, float]:
        """Wire centre (x, y) in mm (touching the hole wall at the top)."""
        return (0.0, 0.5 * self.hole_mm - 0.5 * self.wire_mm)

    def scaled(self, factor: float, name: str = "") -> Structure:
        """All diameters multiplied by ``factor`` (length unchanged).

        Parameters
        ----------
        factor : float
            Scale factor (unitless), > 0.
        name : str
            Label of the scaled structure.

        Returns
        -------
        Structure
        """
        f = check_positive("scale factor", factor)
        return Structure(
            self.hole_mm * f,
            self.tube_od_mm * f,
            self.tube_id_mm * f,
            self.wire_mm * f,
            self.length_mm,
            name or self.name,
        )

    def to_dict(self) -> dict[str, float | str]:
        """JSON-ready dict (mm), including the derived clearance and wall."""
        d: dict[str, float | str] = dict(asdict(self))
        d["clearance_mm"] = self.clearance_mm
        d["wall_mm"] = self.wall_mm
        return d


#: The paper's base group (Table 3, test 1) with the default inner diameter 4.97 mm
#: (the paper does not print the ID; this is a working value, see calibration).
BASE = Structure(10.0, 8.3, 4.97, 1.6, 116.0, "base (test 1)")
