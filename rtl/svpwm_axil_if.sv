// SPDX-License-Identifier: Apache-2.0
// svpwm_axil_if: AXI4-Lite slave (32-bit data, wstrb) to the one-cycle register port of svpwm_regs.
// The write address and the write data are taken independently (either may come first) and held;
// the write is issued when both are there and the write response slot is free. A read is issued in
// the clock its address is accepted; svpwm_regs answers the clock after, held until RREADY.
// Writes have priority over a read in the same clock; a read can still go every other clock.
// Parameters:
//   AddrWidth - byte address width (the register block decodes every bit; [1:0] are ignored)
// Latency: write: AW/W accepted -> 1 clock -> issued (BVALID the clock after); read: AR accepted
//   (issued) -> RVALID the next clock. One write and one read outstanding at most.
// Restrictions: BRESP / RRESP are always OKAY (addresses without a register read 0, writes to them
//   are ignored); AWPROT / ARPROT are not used and therefore not ports.
`default_nettype none

module svpwm_axil_if #(
  parameter int AddrWidth = 8
) (
  input  logic                 clk_i,             // clock (ACLK)
  input  logic                 rst_ni,            // asynchronous reset, active low (ARESETn)
  // AXI4-Lite slave
  input  logic [AddrWidth-1:0] axil_awaddr_i,     // write address (byte)
  input  logic                 axil_awvalid_i,
  output logic                 axil_awready_o,
  input  logic [31:0]          axil_wdata_i,
  input  logic [3:0]           axil_wstrb_i,      // byte lanes to write
  input  logic                 axil_wvalid_i,
  output logic                 axil_wready_o,
  output logic [1:0]           axil_bresp_o,      // always OKAY
  output logic                 axil_bvalid_o,
  input  logic                 axil_bready_i,
  input  logic [AddrWidth-1:0] axil_araddr_i,     // read address (byte)
  input  logic                 axil_arvalid_i,
  output logic                 axil_arready_o,
  output logic [31:0]          axil_rdata_o,
  output logic [1:0]           axil_rresp_o,      // always OKAY
  output logic                 axil_rvalid_o,
  input  logic                 axil_rready_i,
  // register port (svpwm_regs)
  output logic                 req_o,             // one access this clock
  output logic                 we_o,              // 1 write, 0 read
  output logic [AddrWidth-1:0] addr_o,            // byte address
  output logic [31:0]          wdata_o,
  output logic [3:0]           be_o,
  input  logic [31:0]          rdata_i            // read data, the clock after a read request
);

  logic                 aw_full_d, aw_full_q, w_full_d, w_full_q;
  logic [AddrWidth-1:0] awaddr_d, awaddr_q;
  logic [31:0]          wdata_d, wdata_q;
  logic [3:0]           wstrb_d, wstrb_q;
  logic                 bvalid_d, bvalid_q, rvalid_d, rvalid_q;
  logic                 issue_wr, issue_rd;

  // ready depends only on state, never on a valid (no combinational path through the slave)
  assign issue_wr       = aw_full_q && w_full_q && !bvalid_q;
  assign axil_awready_o = !aw_full_q;
  assign axil_wready_o  = !w_full_q;
  assign axil_arready_o = !rvalid_q && !issue_wr;
  assign issue_rd       = axil_arvalid_i && axil_arready_o;

  always_comb begin
    aw_full_d = aw_full_q;
    awaddr_d  = awaddr_q;
    w_full_d  = w_full_q;
    wdata_d   = wdata_q;
    wstrb_d   = wstrb_q;
    bvalid_d  = bvalid_q;
    rvalid_d  = rvalid_q;
    if (issue_wr) begin
      aw_full_d = 1'b0;
      w_full_d  = 1'b0;
      bvalid_d  = 1'b1;
    end
    if (axil_awvalid_i && axil_awready_o) begin
      aw_full_d = 1'b1;
      awaddr_d  = axil_awaddr_i;
    end
    if (axil_wvalid_i && axil_wready_o) begin
      w_full_d = 1'b1;
      wdata_d  = axil_wdata_i;
      wstrb_d  = axil_wstrb_i;
    end
    if (bvalid_q && axil_bready_i) bvalid_d = 1'b0;
    if (issue_rd)                  rvalid_d = 1'b1;
    if (rvalid_q && axil_rready_i) rvalid_d = 1'b0;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      aw_full_q <= 1'b0;
      awaddr_q  <= '0;
      w_full_q  <= 1'b0;
      wdata_q   <= '0;
      wstrb_q   <= '0;
      bvalid_q  <= 1'b0;
      rvalid_q  <= 1'b0;
    end else begin
      aw_full_q <= aw_full_d;
      awaddr_q  <= awaddr_d;
      w_full_q  <= w_full_d;
      wdata_q   <= wdata_d;
      wstrb_q   <= wstrb_d;
      bvalid_q  <= bvalid_d;
      rvalid_q  <= rvalid_d;
    end
  end

  assign req_o         = issue_wr || issue_rd;
  assign we_o          = issue_wr;
  assign addr_o        = issue_wr ? awaddr_q : axil_araddr_i;
  assign wdata_o       = wdata_q;
  assign be_o          = wstrb_q;
  assign axil_bvalid_o = bvalid_q;
  assign axil_bresp_o  = 2'b00;
  assign axil_rvalid_o = rvalid_q;
  assign axil_rresp_o  = 2'b00;
  assign axil_rdata_o  = rdata_i;

endmodule

`default_nettype wire
