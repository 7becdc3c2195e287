"""powderfmu's Python side: the FMI units of the contact mechanics of cohesive powders inside system
models, and parameter sweeps on Dask. fmpy does the FMI work.

- `powderfmu.fmu_path(unit)`: the built .fmu files;
- `powderfmu.start_values(fmu, scene)`: a scene JSON as a unit's start values;
- `powderfmu.sieve`: an ultrasonic sieve (a vibrated plate and N adhering particles, two-way coupled);
- `python -m powderfmu.sweep SPEC.json`: sweeps on dask.distributed.
"""

from .fmus import FmuNotFound, fmu_path
from .scene import start_values

__version__ = "0.1.0"
__all__ = ["FmuNotFound", "fmu_path", "start_values", "__version__"]
