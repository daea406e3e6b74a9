from os import PathLike
from typing import Any, Literal, overload

import numpy as np

def write(path: str | PathLike[str], image: Any, metadata: dict[str, Any] | None = ...,
          channels: list[str] | None = ...) -> None: ...
@overload
def read(path: str | PathLike[str], with_channel_names: Literal[False] = ...) -> tuple[np.ndarray, dict[str, str]]: ...
@overload
def read(path: str | PathLike[str], with_channel_names: Literal[True]) -> tuple[np.ndarray, dict[str, str], list[str]]: ...
