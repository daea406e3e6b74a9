from .thin_film import *  # deprecated alias of iris.thin_film
