"""`python -m washer.paper`: washer.paper.job.main."""
from washer.paper.job import main

raise SystemExit(main())
