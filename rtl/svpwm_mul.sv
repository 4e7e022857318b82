// SPDX-License-Identifier: Apache-2.0
// svpwm_mul: svpwm_calc's 16 x 16 unsigned multiplier. Dsp = 1: operand registers A, B and the product
// register P <= A * B every clock, written so that Yosys maps it to one registered SB_MAC16 on the UP5K
// (its input and output registers: nextpnr models the MAC16's internal delays as ~0 ns, so only the
// registered DSP gives an honest Fmax) and to a LUT multiplier elsewhere. Dsp = 0: a serial shift-add
// unit for devices without a DSP: loading B starts 16 iterations, the product is in P after them.
// Parameters: Dsp - the registered multiplier (1) or the serial unit (0).
// Latency: Dsp = 1: P = A * B two clocks after the last load; Dsp = 0: P = A * B 16 clocks after the
// clock that loads B (A may be loaded in the same clock or before, and must hold until then).
// Restrictions: Dsp = 1: A, B and P have no reset (they are the DSP's registers): X after reset until
// loaded. Dsp = 0: P holds partial sums while the unit runs; a load of B restarts it.
`default_nettype none

module svpwm_mul #(
  parameter bit Dsp = 1'b1
) (
  input  logic        clk_i,    // core clock
  input  logic        rst_ni,   // asynchronous reset, active low
  input  logic        la_i,     // A <- a_i
  input  logic [15:0] a_i,
  input  logic        lb_i,     // B <- b_i (Dsp = 0: start)
  input  logic [15:0] b_i,
  output logic [31:0] p_o       // the product register
);

  logic [15:0] a_d, a_q;

  assign a_d = la_i ? a_i : a_q;

  if (Dsp) begin : gen_dsp
    logic [15:0] b_d, b_q;
    logic [31:0] p_q;

    assign b_d = lb_i ? b_i : b_q;

    // no reset: SB_MAC16's input and output registers have none, and with one Yosys leaves these 64
    // registers in the fabric and the DSP unregistered. The calculator loads A and B before it reads P.
    always_ff @(posedge clk_i) begin
      a_q <= a_d;
      b_q <= b_d;
      p_q <= a_q * b_q;
    end
    assign p_o = p_q;

    logic unused_rst;
    assign unused_rst = rst_ni;
  end else begin : gen_serial
    // P = {hi, lo}: lo starts as B and shifts out; each step adds A to hi when lo[0] is set
    logic [31:0] p_d, p_q;
    logic [4:0]  n_d, n_q;
    logic [16:0] hi;

    assign hi = {1'b0, p_q[31:16]} + (p_q[0] ? {1'b0, a_q} : 17'd0);
    always_comb begin
      p_d = p_q;
      n_d = n_q;
      if (lb_i) begin
        p_d = {16'd0, b_i};
        n_d = 5'd16;
      end else if (n_q != 5'd0) begin
        p_d = {hi, p_q[15:1]};
        n_d = n_q - 5'd1;
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        a_q <= '0;
        p_q <= '0;
        n_q <= '0;
      end else begin
        a_q <= a_d;
        p_q <= p_d;
        n_q <= n_d;
      end
    end
    assign p_o = p_q;
  end

endmodule

`default_nettype wire
