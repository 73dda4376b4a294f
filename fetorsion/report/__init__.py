"""Stage 7, the report: ``fetorsion run`` (:mod:`.pipeline`, every analysis of a crank into
one folder, written atomically), its Markdown (:mod:`.markdown`) and off-screen pictures
(:mod:`.render`). Computes nothing of its own: it calls the stages and presents results.
"""
