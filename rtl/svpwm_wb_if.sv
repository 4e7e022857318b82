// SPDX-License-Identifier: Apache-2.0
// svpwm_wb_if: Wishbone B4 slave (32-bit data, 8-bit granularity, SEL) to the one-cycle register port
// of svpwm_regs. Pipelined mode: STALL is never raised, one access per clock, ACK the clock after
// each accepted STB. Classic mode: one access per STB, ACK the clock after it (registered feedback),
// the next access two clocks later.
// Parameters:
//   AddrWidth - byte address width: ADR is a BYTE address (the register map's offsets); ADR[1:0] are
//               ignored. A word-addressed master (LiteX) connects {adr, 2'b00}.
//   Pipelined - 1: B4 pipelined (STALL output, always 0), 0: B4 classic (master holds STB until ACK)
// Latency: ACK and read data the clock after the access is accepted.
// Restrictions: ERR and RTY are not used (addresses without a register read 0, writes to them are
//   ignored); a classic master must not be connected in pipelined mode (it would get two accesses).
`default_nettype none

module svpwm_wb_if #(
  parameter int AddrWidth = 8,
  parameter bit Pipelined = 1'b1
) (
  input  logic                 clk_i,        // clock (CLK_I)
  input  logic                 rst_ni,       // asynchronous reset, active low (RST_I inverted)
  // Wishbone B4 slave
  input  logic                 wb_cyc_i,
  input  logic                 wb_stb_i,
  input  logic                 wb_we_i,
  input  logic [AddrWidth-1:0] wb_adr_i,     // byte address
  input  logic [31:0]          wb_dat_i,
  input  logic [3:0]           wb_sel_i,     // byte lanes
  output logic [31:0]          wb_dat_o,
  output logic                 wb_ack_o,
  output logic                 wb_stall_o,   // pipelined mode only; always 0
  // register port (svpwm_regs)
  output logic                 req_o,
  output logic                 we_o,
  output logic [AddrWidth-1:0] addr_o,
  output logic [31:0]          wdata_o,
  output logic [3:0]           be_o,
  input  logic [31:0]          rdata_i
);

  logic ack_d, ack_q;

  always_comb begin
    req_o = wb_cyc_i && wb_stb_i;
    if (!Pipelined) req_o = req_o && !ack_q;   // classic: STB is still high in the ACK clock
    ack_d = req_o;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) ack_q <= 1'b0;
    else         ack_q <= ack_d;
  end

  assign we_o       = wb_we_i;
  assign addr_o     = wb_adr_i;
  assign wdata_o    = wb_dat_i;
  assign be_o       = wb_sel_i;
  assign wb_dat_o   = rdata_i;
  assign wb_ack_o   = ack_q;
  assign wb_stall_o = 1'b0;

endmodule

`default_nettype wire
