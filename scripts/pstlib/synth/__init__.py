"""Silicon figures of a hardware profile: the synthesis flow (flow: Yosys to the OSU018 cells,
the memories alone, OpenSTA), the report's blocks read off the elaborated hierarchy (blocks),
the JSON record and its Markdown (report), the per-module area cache of the search (modules),
and the tool pieces they share (tools, liberty, sta, memarea, fanout)."""
