"""What pyproject.toml cannot say: the packages are every subpackage of the three layers (found, not listed by
hand), the folders ``geometry/`` and ``fem/`` installed as ``ltca.geometry`` and ``ltca.fem`` (one import
namespace: no clash with other distributions named ``geometry`` or ``fem``), plus the repository's ``cases/`` and
``studies/`` folders, installed as ``ltca/cases`` and ``ltca/studies`` so that a shipped case is found by name after
a plain ``pip install .`` (:mod:`ltca.shipped`)."""
from setuptools import find_packages, setup

#: installed package -> folder of the repository: the two lower layers, then the data folders
LAYER_DIRS = {"ltca.geometry": "geometry", "ltca.fem": "fem"}
DATA_DIRS = {"ltca.cases": "cases", "ltca.cases.crosscheck": "cases/crosscheck", "ltca.studies": "studies"}

setup(
    packages=find_packages(include=["ltca*"])
    + [f"ltca.{name}" for name in find_packages(include=["geometry*", "fem*"])] + list(DATA_DIRS),
    package_dir={**LAYER_DIRS, **DATA_DIRS},
    package_data={"ltca.cylindrical": ["templates/*.j2"], "ltca.bevel": ["templates/*.j2"], "ltca.rexs": ["data/*"],
                  **{pkg: ["*.toml"] for pkg in DATA_DIRS}},
)
