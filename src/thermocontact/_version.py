"""The package version, in one place (read by the build as well)."""

#: The package version.
__version__ = "1.0.0"
