// pst_noise_tree: the noise unit's interpolation tree (part of rtl/noise/pst_noise.sv, unit 2
// of docs/HARDWARE.md, steps 5 and the pipeline boundaries b2..b5): the registers after the
// corners, the lerps inside a step and the serial lerps across steps, down to the root node.
// Golden: pst::noiseFx (model/golden/noise_fx.cpp).
//
// 5. Lerps (pst_noise_lerp): L(x, y) = x + floor((y - x) s / 2^LF) on v; on the three
//    derivatives L_F(x, y) = x + 2^F floor(((y - x) / 2^F) s / 2^LF) (= L when F = 0); the
//    derivative on the lerp's own axis adds 2^F floor(floor((b.v - a.v) / 2^F) ds / 2^LF).
//    Every derivative is a multiple of 2^F: its F low bits are constant zeros in every lerp
//    and register (the products and registers narrow; F = 0 is the exact unit).
//    x: nodes 0..3 from corners (2j, 2j+1); y: nodes 4, 5 from (0, 1), (2, 3); z: node 6.
//
// Serial evaluation (NoiseSteps = 2, 4, 8): step j brings corners j CPS .. j CPS + CPS-1
// (CPS = 8 / NoiseSteps), lerped here on the first KC = lg CPS axes; the remaining axes are
// lerped across steps through one lerp and one held node per axis (the node of a step with
// bit l = 0 is held, the next step's node is lerped with it). The lerps are the tree's lerps on
// the same operands, so the root is the same bit for bit.
//
// Boundaries (as pst_noise): a register (pst_delay, enabled by en_i) at boundary b2 + t after
// tree level t (t = 0: the corners) and b2 + KC + 1 + l after serial level l, when that
// boundary is below NoiseRegs. The token (valid, step) and the weights travel beside the
// nodes through the same boundaries; a serial level's held node stores when the token at that
// level has its bit l = 0.
//
// Parameters:
//   NoiseInterp, NoiseCorner, NoiseValueFrac, NoiseLatticeFrac, NoiseSteps, NoiseRegs
//               the profile's noise parameters (pst_noise): the lerps' weight function, what
//               the corners' derivative lanes can hold, LF, the levels built, the registers
//   NodeFrac    fraction bits of every node (NoiseOutFrac + NoiseGuardBits)
//   GradFloor   F: the derivative lanes are multiples of 2^F (their F low bits are not
//               registered)
//
// Ports:
//   tok_i   {valid, step} of the corners; tok_o the same token at the root
//   wts_i   the weights beside the corners: s of axis k at [k*LF +: LF], ds at
//           [3*LF + k*(LF+2) +: LF+2]
//   corner_i  the step's CPS corner nodes, node i at [i*NodeW +: NodeW] (v at [0 +: VW], g_k at
//             [VW + k*GW +: GW])
//   root_o  the root node (valid with tok_o when its step is the last)
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_noise_tree #(
  `PST_TREE_PARAMS,
  parameter int NodeFrac = 20,
  parameter int GradFloor = 0,
  localparam int LF = NoiseLatticeFrac,
  localparam int VW = 3 + NodeFrac,         // node value Q3.NodeFrac
  localparam int GW = 5 + NodeFrac,         // node derivative Q5.NodeFrac
  localparam int NodeW = VW + 3 * GW,
  localparam int CPS = 8 / NoiseSteps,      // corners per step
  localparam int TW = 4,                    // token: {valid, step}
  localparam int WTW = 3 * LF + 3 * (LF + 2)
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   en_i,
  input  logic [TW-1:0]          tok_i,
  input  logic [WTW-1:0]         wts_i,
  input  logic [CPS*NodeW-1:0]   corner_i,
  output logic [TW-1:0]          tok_o,
  output logic [NodeW-1:0]       root_o
);

  localparam int KC = $clog2(CPS);          // lerp levels inside a step (axes 0..KC-1)
  localparam int LS = $clog2(NoiseSteps);   // serial levels (axes KC..2)
  localparam int NT = 1 + KC + LS;          // boundaries here: b2 .. b2 + NT - 1

  // ---- token and weights beside the nodes ---------------------------------------------------
  // tok[j], wts[j]: after boundary b(1+j) (j = 0: the inputs, beside the corners).
  logic [(NT+1)*TW-1:0]  tok;
  logic [(NT+1)*WTW-1:0] wts;
  assign tok[0 +: TW]  = tok_i;
  assign wts[0 +: WTW] = wts_i;
  for (genvar j = 0; j < NT; j++) begin : g_beside
    pst_delay #(.Width(TW), .Depth(2 + j < NoiseRegs ? 1 : 0), .Reset(1'b1)) u_tok (
      .clk_i, .rst_ni, .en_i, .d_i (tok[j*TW +: TW]), .q_o (tok[(j+1)*TW +: TW])
    );
    pst_delay #(.Width(WTW), .Depth(2 + j < NoiseRegs ? 1 : 0)) u_wts (
      .clk_i, .rst_ni, .en_i, .d_i (wts[j*WTW +: WTW]), .q_o (wts[(j+1)*WTW +: WTW])
    );
  end
  assign tok_o = tok[NT*TW +: TW];

  // ---- what the derivative lanes hold -------------------------------------------------------
  // What is known of the corners' derivative lanes (pst_noise_lerp's GradHi, GradLo: values
  // are multiples of 2^Lo and fit Hi bits signed), exact:
  //   value_gradient: R at NodeFrac, R in [-1, 1): Hi = NodeFrac + 1; Lo = NodeFrac - VF when
  //                   VF < NodeFrac (R << (NodeFrac - VF)), else 0 (floored);
  //   value:          0: Hi = 1, Lo = 0;
  //   grad12:         -1, 0, +1: Hi = NodeFrac + 2, Lo = NodeFrac;
  //   and every lane is a multiple of 2^GradFloor (Lo >= GradFloor; value corners' zero
  //   lanes: Hi = GradFloor + 1).
  // A lerp on axis a keeps lane k != a between its inputs (Hi unchanged) and leaves
  // max(GradFloor, Lo - LF) zero bits (2^F floor((y - x) s / 2^(LF + F)) with y - x a
  // multiple of 2^Lo); lane a gets the own-axis term: Q5, Hi = GW, Lo = GradFloor. Axes are
  // lerped in the order x, y, z, so after `done` lerps lanes k < done are (GW, GradFloor) and
  // the others (CornerGHi, max(GradFloor, CornerGLo - done LF)).
  localparam int CornerGLo0 = (NoiseCorner == pst_pkg::NoiseCornerValueGradient) ?
                                (NoiseValueFrac < NodeFrac ? NodeFrac - NoiseValueFrac : 0) :
                              (NoiseCorner == pst_pkg::NoiseCornerGrad12) ? NodeFrac : 0;
  localparam int CornerGLo = (CornerGLo0 > GradFloor) ? CornerGLo0 : GradFloor;
  localparam int CornerGHi = (NoiseCorner == pst_pkg::NoiseCornerValueGradient) ? NodeFrac + 1 :
                             (NoiseCorner == pst_pkg::NoiseCornerGrad12) ? NodeFrac + 2 :
                             GradFloor + 1;
  // A node's significant bits (registers, held nodes): v, then each derivative above its
  // GradFloor zeros (PackW = NodeW when GradFloor = 0).
  localparam int PGW = GW - GradFloor;
  localparam int PackW = VW + 3 * PGW;
  /* verilator lint_off UNUSEDSIGNAL */   // n's GradFloor zeros below each derivative
  function automatic logic [PackW-1:0] pack_node(input logic [NodeW-1:0] n);
    pack_node = {n[VW + 2*GW + GradFloor +: PGW], n[VW + GW + GradFloor +: PGW],
                 n[VW + GradFloor +: PGW], n[0 +: VW]};
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */
  function automatic logic [NodeW-1:0] unpack_node(input logic [PackW-1:0] p);
    unpack_node = {GW'(p[VW + 2*PGW +: PGW]) << GradFloor, GW'(p[VW + PGW +: PGW]) << GradFloor,
                   GW'(p[VW +: PGW]) << GradFloor, p[0 +: VW]};
  endfunction
  function automatic int lane_hi(input int k, input int done);
    lane_hi = (k < done) ? GW : CornerGHi;
  endfunction
  function automatic int lane_lo(input int k, input int done);
    lane_lo = (k < done) ? GradFloor :
              (CornerGLo - done * LF > GradFloor) ? CornerGLo - done * LF : GradFloor;
  endfunction

  // ---- the levels inside a step -------------------------------------------------------------
  // tree_d / tree_q: level 0 = the step's corners, level t = the lerps on axis t-1 (CPS >> t
  // nodes); node k of level t at [(t*CPS + k)*NodeW +: NodeW]. Level t is registered at
  // boundary b2 + t.
  logic [(KC+1)*CPS*NodeW-1:0] tree_d, tree_q;
  assign tree_d[0 +: CPS*NodeW] = corner_i;
  for (genvar t = 0; t <= KC; t++) begin : g_level
    // Boundary b2 + t after level t: the nodes' significant bits only (PackW each: the
    // derivatives' GradFloor low zeros are not registered).
    logic [(CPS >> t)*PackW-1:0] pk_d, pk_q;
    for (genvar k = 0; k < (CPS >> t); k++) begin : g_pack
      // (plain slices, no function: Verilator then sees no loop through the flat tree_d/q)
      localparam int N0 = (t*CPS + k)*NodeW;
      assign pk_d[k*PackW +: VW] = tree_d[N0 +: VW];
      assign tree_q[N0 +: VW] = pk_q[k*PackW +: VW];
      for (genvar m = 0; m < 3; m++) begin : g_lane
        assign pk_d[k*PackW + VW + m*PGW +: PGW] = tree_d[N0 + VW + m*GW + GradFloor +: PGW];
        assign tree_q[N0 + VW + m*GW + GradFloor +: PGW] = pk_q[k*PackW + VW + m*PGW +: PGW];
        if (GradFloor > 0) begin : g_zeros
          assign tree_q[N0 + VW + m*GW +: GradFloor] = '0;
          logic unused_zeros;   // the floor's zeros, not registered
          assign unused_zeros = ^tree_d[N0 + VW + m*GW +: GradFloor];
        end
      end
    end
    pst_delay #(.Width((CPS >> t)*PackW), .Depth(2 + t < NoiseRegs ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i (pk_d), .q_o (pk_q)
    );
    if ((CPS >> t) < CPS) begin : g_unused_slots
      // The rest of the level's slots are unused.
      assign tree_d[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW] = '0;
      assign tree_q[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW] = '0;
      logic unused_slots;
      assign unused_slots = ^{tree_d[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW],
                              tree_q[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW]};
    end
    if (t > 0) begin : g_lerps
      // Level t (axis t-1) lerps nodes 2k, 2k+1 of level t-1, with the weights after b(1+t).
      for (genvar k = 0; k < (CPS >> t); k++) begin : g_lerp
        pst_noise_lerp #(
          `PST_WEIGHT_PASS,
          .NodeFrac         (NodeFrac),
          .Axis             (t - 1),
          .GradHi0          (lane_hi(0, t - 1)),
          .GradHi1          (lane_hi(1, t - 1)),
          .GradHi2          (lane_hi(2, t - 1)),
          .GradLo0          (lane_lo(0, t - 1)),
          .GradLo1          (lane_lo(1, t - 1)),
          .GradLo2          (lane_lo(2, t - 1)),
          .GradFloor        (GradFloor)
        ) u_lerp (
          .a_i    (tree_q[((t-1)*CPS + 2*k)*NodeW +: NodeW]),
          .b_i    (tree_q[((t-1)*CPS + 2*k + 1)*NodeW +: NodeW]),
          .s_i    (wts[t*WTW + (t-1)*LF +: LF]),
          .ds_i   (wts[t*WTW + 3*LF + (t-1)*(LF+2) +: LF+2]),
          .node_o (tree_d[(t*CPS + k)*NodeW +: NodeW])
        );
      end
    end
  end

  // ---- the levels across steps (NoiseSteps > 1) ---------------------------------------------
  // Serial level l (axis KC + l), after boundary b(2+KC+l). At step j the node of the step
  // climbs level l if bit l of j is 1 (it is then the upper node b, the lower one a having been
  // held at step j - 2^l); a node reaching level l with bit l = 0 is held there. The last step
  // (all bits 1) climbs every level to the root.
  logic [(LS+1)*NodeW-1:0] chain;   // node entering serial level l at [l*NodeW +: NodeW]
  assign chain[0 +: NodeW] = tree_q[(KC*CPS)*NodeW +: NodeW];
  for (genvar l = 0; l < LS; l++) begin : g_serial
    localparam int B = 3 + KC + l;   // the boundary of this level's register
    localparam int J = B - 2;        // the token and weights of this level: after b(B-1)
    logic [TW-1:0]    tk;
    logic [NodeW-1:0] hold, node_d, node_q;
    logic [PackW-1:0] hold_q, pk_q;   // significant bits only (pack_node)
    logic             lower_ones;   // bits 0..l-1 of the step are all 1
    assign tk = tok[J*TW +: TW];
    logic unused_tk;   // the step bits above l
    assign unused_tk = ^tk;
    if (l == 0) begin : g_l0
      assign lower_ones = 1'b1;
    end else begin : g_ln
      assign lower_ones = &tk[l-1:0];
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) hold_q <= '0;
      else if (en_i && tk[3] && lower_ones && !tk[l]) hold_q <= pack_node(chain[l*NodeW +: NodeW]);
    end
    assign hold = unpack_node(hold_q);
    pst_noise_lerp #(
      `PST_WEIGHT_PASS,
      .NodeFrac         (NodeFrac),
      .Axis             (KC + l),
      .GradHi0          (lane_hi(0, KC + l)),
      .GradHi1          (lane_hi(1, KC + l)),
      .GradHi2          (lane_hi(2, KC + l)),
      .GradLo0          (lane_lo(0, KC + l)),
      .GradLo1          (lane_lo(1, KC + l)),
      .GradLo2          (lane_lo(2, KC + l)),
      .GradFloor        (GradFloor)
    ) u_lerp (
      .a_i    (hold),
      .b_i    (chain[l*NodeW +: NodeW]),
      .s_i    (wts[J*WTW + (KC+l)*LF +: LF]),
      .ds_i   (wts[J*WTW + 3*LF + (KC+l)*(LF+2) +: LF+2]),
      .node_o (node_d)
    );
    pst_delay #(.Width(PackW), .Depth(B < NoiseRegs ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i (pack_node(node_d)), .q_o (pk_q)
    );
    assign node_q = unpack_node(pk_q);
    assign chain[(l+1)*NodeW +: NodeW] = node_q;
  end
  assign root_o = chain[LS*NodeW +: NodeW];

  logic unused_wts;   // the weights after the last boundary
  assign unused_wts = ^wts[NT*WTW +: WTW];

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (NoiseSteps != 1 && NoiseSteps != 2 && NoiseSteps != 4 && NoiseSteps != 8)
      $error("pst_noise_tree: NoiseSteps must be 1, 2, 4 or 8");
    if (GradFloor < 0 || GradFloor > NodeFrac)
      $error("pst_noise_tree: GradFloor must be 0..NodeFrac");
  end
`endif

endmodule

`default_nettype wire
