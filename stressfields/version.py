"""The package's version, importing nothing: `cf` stamps it on every file."""

#: the one source of the version (pyproject.toml reads it as stressfields.__version__)
__version__ = "0.1.0"
