"""A learned controller, end to end: demonstrations from the reference MPPI in the offline
runner (``record``), a small policy trained with JAX (``policy``), served as a Controller
(``controller``); ``nav2-pyif learn`` runs the three (``pipeline``)."""
