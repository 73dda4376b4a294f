"""Stage 7, the report: presents what a run computed, computes nothing. The typed outcome of
each analysis (:mod:`.outcomes`), the Markdown (:mod:`.markdown`, its summary in :mod:`.summary` and
its fatigue section in :mod:`.fatigue`), the self-contained web page
(:mod:`.html`) and off-screen mode pictures (:mod:`.render`). The run itself, which calls the
stages and fills the outcomes, is :mod:`fetorsion.app.run`.
"""
