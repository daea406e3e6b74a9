"""Imports the higher layer's package: an upward edge the check must reject."""
import pkg  # noqa: F401
