"""The models of pendula: one module per physical system.

A scene's fields select one model; the model says which of the scene's effects
it accepts and which keep an exact (closed-form) path.  The rigid pendulum is
the first (:mod:`pendula.models.rigid`).
"""
