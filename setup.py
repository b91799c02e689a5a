"""What pyproject.toml cannot say: the packages are every subpackage of the three layers (found, not listed by
hand) plus the repository's ``cases/`` and ``studies/`` folders, installed as ``ltca/cases`` and ``ltca/studies``
so that a shipped case is found by name after a plain ``pip install .`` (:mod:`ltca.shipped`)."""
from setuptools import find_packages, setup

#: installed package -> folder of the repository
DATA_DIRS = {"ltca.cases": "cases", "ltca.cases.crosscheck": "cases/crosscheck", "ltca.studies": "studies"}

setup(
    packages=find_packages(include=["geometry*", "fem*", "ltca*"]) + list(DATA_DIRS),
    package_dir=DATA_DIRS,
    package_data={"ltca.cylindrical": ["templates/*.j2"], "ltca.bevel": ["templates/*.j2"], "ltca.rexs": ["data/*"],
                  **{pkg: ["*.toml"] for pkg in DATA_DIRS}},
)
