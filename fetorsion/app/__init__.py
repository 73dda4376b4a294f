"""Stage 8, the application: ``fetorsion run``, every analysis of one crank (or chain) into
one report folder (:mod:`.run`). Each step calls the stages below, builds what the next steps
share once (the FE model, the condensed crank, the response), and returns a typed outcome
(:mod:`fetorsion.report.outcomes`) that the report presents; the folder is written atomically.
"""
