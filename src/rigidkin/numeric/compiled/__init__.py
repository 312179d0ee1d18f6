"""Compiled code: the generated C of a model's right-hand side and outputs (cffi), its signed cache, and
the batch integrator compiled into the same library."""
