"""Memories of a synthesized profile: their shapes from Yosys' dump of the $mem_v2 cells, a
stand-alone Verilog module per ROM (synthesized alone to OSU018 cells by scripts/synth.py for
its area and its address-to-data delay), and the area model of the RAMs.

Area model (scripts/synth.py writes it into every report):
- ROM: one copy per read port (replication: a cell-built ROM has no storage to share), each
  copy the memory's content and one read port synthesized to OSU018 cells (ABC area mapping).
  A mask ROM of 1999 would be denser: the figure is an upper bound.
- RAM: what the RTL builds, a register file with asynchronous reads (the colour-table, summed-
  area and MIP tables of pst_clut_filter): built from OSU018 flip-flops, the RAM measured here
  (256 x 32, Yosys + OSU018, this flow) costs FLOP_RAM_UM2_PER_BIT (storage and write port) +
  FLOP_RAM_UM2_PER_BIT_PORT per read port (its multiplexer): the figure in the total. Reported
  beside it, what a compiled SRAM would cost if the reads were registered (an SRAM macro reads
  on a clock edge; the RTL does not): one single-port macro per read port, from a per-bit model,
  SRAM_BITCELL_UM2 (the 6T bit cell of GlobalFoundries' published 180 nm SRAM macros,
  gf180mcu_fd_ip_sram datasheets: 13.5 um^2) over SRAM_ARRAY_EFFICIENCY (0.5: decoders, sense
  amplifiers and I/O as much again as the array; an assumption, not a datasheet figure).
  Read delay: RAM_NS_PER_ADDRESS_BIT per address bit (the flip-flop RAM's 1.652 ns over 8
  address bits, measured here by OpenSTA), the stand-in delay in the design's timing.
"""
import hashlib
import re


SRAM_BITCELL_UM2 = 13.5
SRAM_ARRAY_EFFICIENCY = 0.5
FLOP_RAM_UM2_PER_BIT = 157.1        # storage + write port: 256 x 32, 2 ports 2,114,172 um^2,
FLOP_RAM_UM2_PER_BIT_PORT = 50.5    #   3 ports 2,527,668 um^2 (scripts/synth.py)
RAM_NS_PER_ADDRESS_BIT = 1.652 / 8


def ram_model(mem: dict) -> dict:
    """Area of a RAM as the RTL builds it (flip-flop register file, asynchronous reads), the
    SRAM-macro alternative (one per read port, registered reads) and the read delay."""
    bits = mem["size"] * mem["width"]
    p = mem["read_ports"]
    return {"area_um2": bits * (FLOP_RAM_UM2_PER_BIT + p * FLOP_RAM_UM2_PER_BIT_PORT),
            "sram_area_um2": p * bits * SRAM_BITCELL_UM2 / SRAM_ARRAY_EFFICIENCY,
            "delay_ns": round(mem["abits"] * RAM_NS_PER_ADDRESS_BIT, 3)}


def ram_read_area_um2(entry: dict) -> float:
    """The read ports' share of a RAM record entry's area as the RTL builds it (every instance):
    the read multiplexers, FLOP_RAM_UM2_PER_BIT_PORT per bit and port, without the storage flops.
    The power flow's RAM model (pstlib/power/flow.py, step 4)."""
    return entry["instances"] * entry["size"] * entry["width"] * entry["read_ports"] * FLOP_RAM_UM2_PER_BIT_PORT


def _param(block: str, key: str) -> str:
    m = re.search(rf"parameter \\{key} (\S+)", block)
    if not m:
        raise ValueError(f"$mem_v2 dump has no parameter {key}")
    return m.group(1)


def _int_param(block: str, key: str) -> int:
    v = _param(block, key)
    m = re.fullmatch(r"(?:(\d+)'(?:s?b)([01xz]+)|(-?\d+))", v)
    if not m:
        raise ValueError(f"parameter {key}: cannot read {v[:40]!r}")
    if m.group(3) is not None:
        return int(m.group(3))
    bits = m.group(2)
    return int(bits.replace("x", "0").replace("z", "0"), 2)


def parse_memories(text: str) -> list:
    """(module, memory, size, width, abits, offset, read ports, write ports, init) of every
    $mem_v2 cell; the `select -list` lines and the `dump` blocks come in the same order.
    init: the INIT bit string (MSB first, word SIZE-1 first) or None when all undefined."""
    names = [line.strip() for line in text.splitlines() if "/" in line and not line.startswith(" ")
             and not line.startswith("attribute")]
    blocks = re.split(r"\n\s*cell \$mem_v2 ", "\n" + text)[1:]
    if len(names) != len(blocks):
        raise ValueError(f"memory listing mismatch: {len(names)} names, {len(blocks)} cells")
    mems = []
    for name, block in zip(names, blocks):
        module, memory = name.split("/", 1)
        init = None
        m = re.search(r"parameter \\INIT (\d+)'([01xz]+)", block)
        if m and set(m.group(2)) - {"x"}:
            init = m.group(2)
        mems.append({"module": module, "memory": memory, "size": _int_param(block, "SIZE"),
                     "width": _int_param(block, "WIDTH"), "abits": _int_param(block, "ABITS"),
                     "offset": _int_param(block, "OFFSET"), "read_ports": _int_param(block, "RD_PORTS"),
                     "write_ports": _int_param(block, "WR_PORTS"), "init": init})
    return mems


def init_words(mem: dict) -> list:
    """The initial image as integers, word 0 first (undefined bits read as 0)."""
    bits, w, n = mem["init"], mem["width"], mem["size"]
    if bits is None:
        return [0] * n
    if len(bits) != w * n:
        raise ValueError(f"{mem['memory']}: INIT has {len(bits)} bits, want {w} x {n}")
    clean = bits.replace("x", "0").replace("z", "0")
    return [int(clean[(n - 1 - i) * w:(n - i) * w], 2) for i in range(n)]


def is_rom(mem: dict) -> bool:
    return mem["write_ports"] == 0


def memory_verilog(mem: dict, read_ports: int) -> str:
    """A stand-alone module `pst_mem` holding one memory: a ROM with `read_ports` asynchronous
    read ports and its content, or a RAM with one synchronous write port and `read_ports`
    asynchronous read ports (inputs clk, we, wa, wd)."""
    if mem["offset"] != 0:
        raise ValueError(f"{mem['memory']}: memory offset {mem['offset']} not supported")
    a, w, n = mem["abits"], mem["width"], mem["size"]
    ports = [f"input [{a - 1}:0] a{p}" for p in range(read_ports)]
    ports += [f"output [{w - 1}:0] d{p}" for p in range(read_ports)]
    if not is_rom(mem):
        ports = ["input clk", "input we", f"input [{a - 1}:0] wa", f"input [{w - 1}:0] wd"] + ports
    lines = ["module pst_mem(" + ", ".join(ports) + ");", f"  reg [{w - 1}:0] m [0:{n - 1}];"]
    if is_rom(mem):
        lines.append("  initial begin")
        lines += [f"    m[{i}] = {w}'h{v:x};" for i, v in enumerate(init_words(mem))]
        lines.append("  end")
    else:
        lines.append("  always @(posedge clk) if (we) m[wa] <= wd;")
    lines += [f"  assign d{p} = m[a{p}];" for p in range(read_ports)]
    lines.append("endmodule")
    return "\n".join(lines) + "\n"


def synth_ports(mem: dict) -> int:
    """Read ports of the stand-alone synthesis: one for a ROM (replicated per port), all of
    them for a RAM (one storage array shared by its read multiplexers)."""
    return 1 if is_rom(mem) else mem["read_ports"]


def memory_key(mem: dict, salt: str) -> str:
    """Content key of a memory's stand-alone synthesis (shape, content, ports, flow)."""
    text = memory_verilog(mem, synth_ports(mem)) + salt
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def memory_area(mem: dict, synth_area: float) -> float:
    """Area of one instance of the memory with all its read ports, from the stand-alone
    synthesis's area (one port for a ROM, all ports for a RAM)."""
    return synth_area * (mem["read_ports"] if is_rom(mem) else 1)


def port_options(mem: dict, port_area: float, pairs_even_odd: int = 0, quads_mod4: int = 0) -> list:
    """Cost options of a many-ported ROM (port_area: one read port built from cells):
    - replicate: one copy per read port;
    - bank: `pairs_even_odd` pairs of lookups whose addresses always differ in bit 0 (T[v ^ L]
      and T[v ^ (L + 1)]: L and L + 1 differ in bit 0) share one copy split into even and odd
      halves (the same bits, two half-size arrays): copies = ports - pairs;
    - bank mod 4: `quads_mod4` groups of four reads of consecutive addresses (R[m], ..,
      R[m + 3]: distinct modulo 4) share one copy split into four banks: copies = ports - 3 quads;
    - schedule: the lookups over 1 or 2 ports, ceil(ports / k) cycles for what one takes now.
    Returns dicts (option, copies, area, cycles_factor, note)."""
    p = mem["read_ports"]
    out = [{"option": "replicate", "copies": p, "area": p * port_area, "cycles_factor": 1,
            "note": "one copy per read port (as counted in the total)"}]
    if pairs_even_odd:
        c = p - pairs_even_odd
        out.append({"option": "bank even/odd", "copies": c, "area": c * port_area, "cycles_factor": 1,
                    "note": f"{pairs_even_odd} lookup pairs T[v^L], T[v^(L+1)] never collide in bit 0: "
                            "each pair reads one copy split in even/odd halves"})
    if quads_mod4:
        c = p - 3 * quads_mod4
        out.append({"option": "bank by address mod 4", "copies": c, "area": c * port_area, "cycles_factor": 1,
                    "note": f"{quads_mod4} groups of reads R[m..m+3] hit four different banks: each group "
                            "reads one copy split in four quarter-size banks"})
    for k in (2, 1):
        if k < p:
            out.append({"option": f"schedule over {k} port{'s' if k > 1 else ''}", "copies": k,
                        "area": k * port_area, "cycles_factor": -(-p // k),
                        "note": f"{-(-p // k)} cycles for the lookups one cycle holds now"})
    return out
