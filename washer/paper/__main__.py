from washer.paper.job import main

raise SystemExit(main())
