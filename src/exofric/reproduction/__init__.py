"""``exofric reproduce``: the paper's whole study redone, with every number beside the paper's.

:func:`reproduce` runs eight stages in order and returns a frozen :class:`ReproduceResult`;
:mod:`exofric.report` turns it into ``report.html``, figures and ``results.json``. Pure
computation: no printing, no files.

1. Table 2 from Eqs 3-6 (with the printed C10 slip).
2. Calibration (Table 1, Fig 5b): tube ID from the paper's ANSYS columns, Shore from the test.
3. Base squeeze N(P) (Figs 6-7) and what moves N(0.6 MPa).
4. gamma (Eq 7, Fig 4) from SYNTHETIC virtual-rig friction.
5. Prediction for the seven Table 3 structures (Figs 8-10), deviation metrics, ANOVA (Table 4).
6. Cubic fit for test 5 (Eq 8, Fig 11) and the inverse for 54.40 N.
7. Control (Fig 12): six cases (:func:`compare`, :func:`run_case` on a :class:`ControlSetup`),
   settling times beside the paper's.
8. Torque at 0.6 MPa per structure against the knee's 0-40 Nm.

Units: mm, N, MPa, s, Nm; differences in %.

Examples
--------
>>> from exofric.reproduction import ControlSetup, run_case
>>> r = run_case(ControlSetup.default(), "pi", feedforward=True)
>>> round(r.metrics.steady_state_error_n, 3) + 0.0
0.0
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.reproduction._compare import Comparison, paper_checks, printed_decimals
    from exofric.reproduction._control import ControlStage, CubicStage, stage_control, stage_cubic
    from exofric.reproduction._fig12 import (
        PAPER_SETTLING_S,
        CaseResult,
        CompareResult,
        ControlSetup,
        FrictionMapLike,
        compare,
        run_case,
    )
    from exofric.reproduction._pipeline import (
        FAST_INFLATION_MESH,
        FAST_SQUEEZE_MESH,
        STAGES,
        ReproduceConfig,
        ReproduceResult,
        StageTime,
        reproduce,
        software_versions,
    )
    from exofric.reproduction._predict import (
        PredictionStage,
        TorqueStage,
        stage_prediction,
        stage_torque,
    )
    from exofric.reproduction._squeeze import (
        ID_STEP_MM,
        GammaStage,
        SqueezeStage,
        stage_gamma,
        stage_squeeze,
    )
    from exofric.reproduction._stages import (
        CalibrationStage,
        Table2Stage,
        stage_calibration,
        stage_table2,
    )


# Lazy facade (PEP 562): importing one name does not load every stage of the pipeline; each name
# is loaded from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
