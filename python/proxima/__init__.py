"""proxima: approximate representations of 3D scenes, measured against an Embree reference.

Everything is re-exported from the compiled extension ``proxima._proxima``; docs/python.md
describes the API, the dtypes, shapes and coordinate spaces of its arrays.
"""

from ._proxima import *  # noqa: F401,F403
from ._proxima import __doc__  # noqa: F401
