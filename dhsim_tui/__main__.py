"""``python -m dhsim_tui`` runs the same command line as ``dhsim``."""

from dhsim_tui.cli.main import main

raise SystemExit(main())
