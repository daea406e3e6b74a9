from . import color as color, film as film, materials as materials, thin_film as thin_film
from ._iris import Error as Error, Scene as Scene
from .images import read as read, write as write
from .materials import Material as Material
from .render import RenderInterrupted as RenderInterrupted, RenderResult as RenderResult
from .render import load_file as load_file, load_string as load_string, render as render

__version__: str

def source_path(relative: str) -> str: ...
