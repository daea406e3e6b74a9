"""Deprecated alias of `iris.thin_film` (the thin-film optics): "film" now names only the image
(render/film*, the `<film>` of a scene). Every name is forwarded to `iris.thin_film` with a
DeprecationWarning; the alias will be removed in the next release."""
import warnings as _warnings

from . import thin_film as _thin_film


def __getattr__(name):
    if name.startswith("__"):
        raise AttributeError(name)
    _warnings.warn(f"iris.film.{name} is deprecated: use iris.thin_film.{name}", DeprecationWarning, stacklevel=2)
    return getattr(_thin_film, name)


def __dir__():
    return dir(_thin_film)
