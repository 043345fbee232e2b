"""Where sharded jobs run: the local backend (threads, child processes an interrupt stops: local)
and the SLURM backend (job arrays: slurm), used by the sweep, the search and the sharded
regression (regress_shards: its plan, shards and merge)."""
