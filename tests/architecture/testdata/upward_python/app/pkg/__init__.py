"""A package of the higher layer."""
