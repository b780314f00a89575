"""Material calibration from air-tube inflation tests (paper §3.3, Eqs 2-6, Table 1, Fig 5).

The paper identified the silicone's Shore A hardness by simulating the tube's
outer diameter at the tested pressures for trial hardnesses (Eqs 3-6 give the
Mooney-Rivlin constants) and stopping when the average relative diameter error
fell below 0.5% (60 -> 1.47%, 65 -> 0.87%, 70 -> 2.47%, 62.5 -> 0.46%). The tube's
inner diameter is not printed, so exofric can identify it too.

:func:`calibrate` is the entry point; the methods live in
:mod:`exofric.calibration`, the forward models (FE, 1D, the paper's own
columns) in :mod:`exofric.calibration`, data and results in
:mod:`exofric.calibration`.

Units: mm, MPa, errors in %, time in s.

Examples
--------
>>> from exofric.calibration import InflationData, calibrate
>>> r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=4.97, model="paper-table1")
>>> [t.shore for t in r.history], r.shore, round(r.average_error_pct, 2)
([60.0, 65.0, 70.0, 62.5], 62.5, 0.46)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.calibration._api import METHODS, calibrate
    from exofric.calibration._material import (
        CONDITION_LIMIT,
        CORRELATION_LIMIT,
        DatasetFit,
        Identifiability,
        MaterialCalibration,
        MisfitProfile,
        RingTest,
        calibrate_material,
    )
    from exofric.calibration._methods import (
        Evaluator,
        Fit,
        bisection,
        bounded,
        joint,
        known_hardness,
    )
    from exofric.calibration._models import (
        DEFAULT_MODEL,
        MODEL_KINDS,
        C10Convention,
        CachedModel,
        ModelFn,
        make_model,
        material_for,
        paper_table1_model,
    )
    from exofric.calibration._result import (
        CalibrationResult,
        InflationData,
        Trial,
        relative_errors_pct,
    )


# Lazy facade (PEP 562): ``CalibrationResult`` or ``InflationData`` do not load scipy.optimize
# (``calibrate`` does); each name is loaded from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
