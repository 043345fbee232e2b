"""Each distinct memory synthesized alone to the cell library: its area and its
address-to-data delay (OpenSTA), cached by content; and the report's memory rows."""
import json
import pathlib
import tempfile

from . import inputs, liberty, memarea, sta
from .tools import ABC_CONSTR, ABC_DELAY_PS, ABC_SCRIPT, base_name, cell_lines, parse_stat_json, run_sta, run_yosys

MEM_LOAD_PF = 0.02        # stand-alone memory: output load; stand-in: address-pin load
MEM_SETUP_NS = 0.2        # stand-in write capture: setup (about DFFPOSX1's)


def mem_flow_salt(lib: pathlib.Path) -> str:
    """What a memory's stand-alone synthesis depends on besides its shape and content: the
    mapping, the load, the code that builds, maps and times it, the cell library's content and
    the tool versions."""
    here = pathlib.Path(__file__).parent
    code = [here / f for f in ("memarea.py", "memories.py", "tools.py", "liberty.py", "sta.py")]
    return inputs.digest([*code, lib], (ABC_SCRIPT, ABC_DELAY_PS, ABC_CONSTR, MEM_LOAD_PF, "mem-flow-2",
                                        *inputs.tool_versions()))


def synth_memory(mem: dict, lib: pathlib.Path, cache: pathlib.Path, yosys: str, sta_bin: str,
                 areas: dict, ff_cells: set) -> dict:
    """One memory alone: OSU018 area and address-to-data delay (cached by content key)."""
    key = memarea.memory_key(mem, mem_flow_salt(lib))
    hit = cache / f"{key}.json"
    if hit.exists():
        rec = json.loads(hit.read_text())
        rec["cached"] = True
        return rec
    ports = memarea.synth_ports(mem)
    with tempfile.TemporaryDirectory(prefix="pst_mem_") as t:
        tmp = pathlib.Path(t)
        (tmp / "mem.v").write_text(memarea.memory_verilog(mem, ports))
        (tmp / "abc.constr").write_text(ABC_CONSTR)
        script = "\n".join([
            f"read_verilog {tmp}/mem.v",
            "synth -top pst_mem -flatten",
            *cell_lines(lib, tmp),
            f"write_verilog -noattr -simple-lhs {tmp}/net.v",
        ]) + "\n"
        secs = run_yosys(script, tmp, "mem", yosys)
        stat = parse_stat_json((tmp / "stat.json").read_text())
        cells = next(iter(stat["modules"].values()))["num_cells_by_type"]
        area = liberty.cells_area(cells, areas)
        ffs = sum(n for c, n in cells.items() if c in ff_cells)
        clock = "create_clock -name clk -period 10 [get_ports clk]" if not memarea.is_rom(mem) else \
            "create_clock -name clk -period 10"
        tcl = "\n".join([
            f"read_liberty {lib}", f"read_verilog {tmp}/net.v", "link_design pst_mem", clock,
            "set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk -quiet]]",
            "set_driving_cell -lib_cell BUFX2 [delete_from_list [all_inputs] [get_ports clk -quiet]]",
            "set_output_delay 0 -clock clk [all_outputs]",
            f"set_load {MEM_LOAD_PF} [all_outputs]",
            f"report_checks -path_delay max -from [get_ports a*] -digits 3 > {tmp}/rep.txt",
            "exit"]) + "\n"
        ssecs, _ = run_sta(tcl, tmp, "mem", sta_bin)
        paths = sta.parse_checks((tmp / "rep.txt").read_text())
        if not paths or paths[0]["arrival"] is None:
            raise RuntimeError(f"memory {mem['memory']}: no address-to-data path in OpenSTA's report")
        rec = {"key": key, "ports_synthesized": ports, "area_um2": area, "cells": sum(cells.values()),
               "flip_flops": ffs, "delay_ns": paths[0]["arrival"], "yosys_seconds": round(secs, 1),
               "sta_seconds": round(ssecs, 1), "cached": False}
    cache.mkdir(parents=True, exist_ok=True)
    hit.write_text(json.dumps(rec, indent=1) + "\n")
    return rec


def memory_rows(mems: list, mem_syn: dict, instances: dict, lib: pathlib.Path, ge: float) -> tuple:
    """The report's memory rows (every memory has at least one instance: RuntimeError if not), the stand-in index ((module, memory) ->
    k) and the stand-ins' delays (k -> ns). mem_syn: content key -> synth_memory's record."""
    memories, mem_index, delays = [], {}, {}
    for i, m in enumerate(mems):
        if memarea.is_rom(m):
            rec = mem_syn[memarea.memory_key(m, mem_flow_salt(lib))]
            each = memarea.memory_area(m, rec["area_um2"])
        else:
            model = memarea.ram_model(m)
            rec = {"delay_ns": model["delay_ns"], "ports_synthesized": 0, "area_um2": 0, "cells": 0,
                   "flip_flops": 0}
            each = model["area_um2"]
        delays[i] = rec["delay_ns"]
        n = instances[(m["module"], m["memory"])]
        if n < 1:
            # Every memory Yosys found is in a module of the design: none means the counting
            # lost it (a name mismatch), not that it costs nothing.
            raise RuntimeError(f"memory {m['module']}.{m['memory']}: no instance in the design's hierarchy")
        mem_index[(m["module"].lstrip("\\"), m["memory"].lstrip("\\"))] = i
        entry = {"module": base_name(m["module"]), "memory": m["memory"].lstrip("\\"),
                 "kind": "ROM" if memarea.is_rom(m) else "RAM", "instances": n,
                 "size": m["size"], "width": m["width"], "read_ports": m["read_ports"],
                 "write_ports": m["write_ports"], "bits_each": m["size"] * m["width"],
                 "area_um2_each": round(each), "ge_each": round(each / ge),
                 "area_um2": round(n * each), "ge": round(n * each / ge),
                 "delay_ns": rec["delay_ns"], "synthesized_ports": rec["ports_synthesized"],
                 "synth_area_um2": round(rec["area_um2"]), "synth_cells": rec["cells"],
                 "synth_flip_flops": rec["flip_flops"], "stand_in": liberty.standin_cell_name(i),
                 "model": "cell-built ROM, one copy per read port" if memarea.is_rom(m) else
                          "flip-flop register file, asynchronous reads (as the RTL builds it)"}
        if not memarea.is_rom(m):
            entry["sram_macro_ge"] = round(n * memarea.ram_model(m)["sram_area_um2"] / ge)
        if memarea.is_rom(m) and m["read_ports"] > 1:
            # The noise unit's tables are banked in the RTL already (hash even/odd, value
            # table by address mod 4: each bank is a memory of its own here), so the
            # options left on a bank are replication (as built) and scheduling.
            entry["port_options"] = [dict(o, area_um2=round(o["area"]), ge=round(o["area"] / ge),
                                          total_ge=round(n * o["area"] / ge))
                                     for o in memarea.port_options(m, rec["area_um2"])]
            for o in entry["port_options"]:
                o.pop("area")
        memories.append(entry)
    return memories, mem_index, delays
