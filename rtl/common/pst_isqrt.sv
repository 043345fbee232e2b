// Integer square root: y_o = floor(sqrt(x_i)), combinational when Regs = 0. The digit-by-digit (restoring)
// method, two input bits per step from the top: one compare-subtract of OutWidth + 2 bits per
// result bit. Used by pst_filter_width for the euclidean |grad_x f|. Golden model: isqrtFx in
// model/golden/arith_fx.cpp (same steps).
//
//   rem = 0, root = 0; for i = OutWidth-1 .. 0:
//     rem  = 4 rem + x[2i+1:2i];  trial = 4 root + 1
//     rem >= trial ? (rem -= trial, root = 2 root + 1) : (root = 2 root)
//   Invariant after each step: root^2 + rem = the leading bits of x consumed so far and
//   rem <= 2 root, so rem fits OutWidth + 2 bits.
//
// Pipelined (Regs > 0): the OutWidth steps are cut into Regs + 1 groups of
// ceil(OutWidth / (Regs + 1)) with a register (pst_delay, enabled by en_i) after each group
// but the last, carrying rem, root and the input bits still to come; y_o comes Regs advances
// after x_i.
//
// Parameters:
//   InWidth   bits of the unsigned input x_i; the result has ceil(InWidth / 2) bits.
//   Regs      pipeline registers (0 .. OutWidth - 1).
`default_nettype none

module pst_isqrt #(
  parameter int InWidth = 32,
  parameter int Regs = 0,
  // Derived width (not a profile key): floor(sqrt(x)) < 2^ceil(InWidth / 2).
  localparam int OutWidth = (InWidth + 1) / 2
) (
  input  logic                clk_i,    // pipeline registers (Regs > 0)
  input  logic                rst_ni,
  input  logic                en_i,
  input  logic [InWidth-1:0]  x_i,
  output logic [OutWidth-1:0] y_o
);

  localparam int PW = 2 * OutWidth;   // x padded to an even number of bits
  localparam int RW = OutWidth + 2;   // remainder and trial width
  localparam int G  = (OutWidth + Regs) / (Regs + 1);   // steps per group
  localparam int SW = RW + OutWidth + PW;               // {rem, root, x}

  // st_in[g]: the state entering group g (after the register before it); st_out[g]: after it.
  logic [(Regs+1)*SW-1:0] st_in, st_out;
  assign st_in[0 +: SW] = {RW'(0), OutWidth'(0), PW'(x_i)};

  for (genvar g = 0; g <= Regs; g++) begin : g_group
    always_comb begin
      logic [PW-1:0]       xp;
      logic [RW-1:0]       rem, trial;
      logic [OutWidth-1:0] root;
      {rem, root, xp} = st_in[g*SW +: SW];
      for (int it = g * G; it < (g + 1) * G; it++) begin
        if (it < OutWidth) begin
          rem   = {rem[RW-3:0], xp[2*(OutWidth-1-it) +: 2]};
          trial = {root, 2'b01};
          if (rem >= trial) begin
            rem  = rem - trial;
            root = (root << 1) | OutWidth'(1);
          end else begin
            root = root << 1;
          end
        end
      end
      st_out[g*SW +: SW] = {rem, root, xp};
    end
    if (g < Regs) begin : g_reg
      pst_delay #(.Width(SW), .Depth(1)) u_reg (
        .clk_i, .rst_ni, .en_i, .d_i (st_out[g*SW +: SW]), .q_o (st_in[(g+1)*SW +: SW])
      );
    end
  end
  assign y_o = st_out[Regs*SW + PW +: OutWidth];
  logic unused_state;
  assign unused_state = ^{st_out[Regs*SW +: PW], st_out[Regs*SW + PW + OutWidth +: RW]};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (Regs >= 0 && Regs < OutWidth) else $error("pst_isqrt: Regs must be 0 .. OutWidth - 1");
  end
  // y_o = floor(sqrt(x)) of the x_i Regs advances ago: y^2 <= x < (y + 1)^2.
  logic [InWidth-1:0] x_chk;
  pst_delay #(.Width(InWidth), .Depth(Regs)) u_x_chk (.clk_i, .rst_ni, .en_i, .d_i (x_i), .q_o (x_chk));
  always_comb begin
    assert ((2*RW)'(y_o) * (2*RW)'(y_o) <= (2*RW)'(x_chk) &&
            ((2*RW)'(y_o) + 1) * ((2*RW)'(y_o) + 1) > (2*RW)'(x_chk))
      else $error("pst_isqrt: y_o is not floor(sqrt(x_i))");
  end
`endif

endmodule

`default_nettype wire
