"""The report sections, one module per seed paper (``TITLE``, ``run(ctx) -> Section``),
found by :data:`bearingsim.report.SECTIONS`."""
