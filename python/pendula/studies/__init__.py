"""The measuring apparatus of pendula, kept apart from the library it measures.

- :mod:`.accuracy`: the elliptic functions and the models against their stored
  mpmath references and closed forms (``pendula accuracy``);
- :mod:`.model_grids`: the models' reference grids and their tolerances;
- :mod:`.workprecision`: what accuracy costs in time, against the peers;
- :mod:`.bench`: speed against the peers (``pendula bench``).

Nothing in the library imports this package.
"""
