"""The eccentric planetary satellite of Kapitonov et al. (Vestnik BRU 2014 No. 4(45)).

Modules: :mod:`.tools` (design and the three tools), :mod:`.forming` (cutting by method), :mod:`.compare`
(deviations from the special hob, plot), :mod:`.wheel` (central wheel by a shaper, choice of z2 and x2),
:mod:`.mesh` (eccentric kinematics, outline distances, free window), :mod:`.interference`,
:mod:`.separation` (unloaded gaps of every pair), :mod:`.rating` (ISO 6336-3 rated torque).
"""
from .compare import FormingComparison, compare_forming, plot_forming, profile_deviation
from .forming import METHODS, FormedTooth, form_satellite
from .interference import InterferenceReport, analyse_interference, minimum_thinning
from .mesh import EccentricMesh
from .rating import RatingInputs, rated_torque
from .separation import UnloadedGaps, unloaded_gaps
from .tools import DiskCutter, HobThreePass, SatelliteDesign, SpecialHob, eq4_rack_thickness
from .wheel import CentralWheelDesign, generate_central_wheel, wheel_shift

__all__ = ["SatelliteDesign", "HobThreePass", "DiskCutter", "SpecialHob", "eq4_rack_thickness", "METHODS",
           "FormedTooth", "form_satellite", "FormingComparison", "compare_forming", "plot_forming",
           "profile_deviation", "CentralWheelDesign", "generate_central_wheel", "wheel_shift", "EccentricMesh",
           "InterferenceReport", "analyse_interference", "minimum_thinning", "UnloadedGaps", "unloaded_gaps",
           "RatingInputs", "rated_torque"]
