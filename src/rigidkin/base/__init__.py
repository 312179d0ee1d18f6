"""The base layer: vocabulary every other layer uses and that knows nothing of mechanics models.

Errors, the derivation trace, printing in dynamics notation, text safety, time limits and resource
limits, private and output files and the cache folder, symbolic algebra (zero tests by random
evaluation, readable forms, trigonometric forms), units and dimensions, the linear solve with safe
pivots and vector operations on components.  Nothing here imports from another rigidkin layer.
"""
