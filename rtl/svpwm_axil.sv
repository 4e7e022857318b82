// SPDX-License-Identifier: Apache-2.0
// svpwm_axil: svpwm_core behind a 32-bit AXI4-Lite slave: svpwm_axil_if + svpwm_mmio (svpwm_regs, generated
// from rdl/svpwm.rdl, map in docs/registers.md, + svpwm_core). Every RW register field drives a core input
// continuously; the core samples its inputs at its load points, so a write takes effect at the next
// load point (carrier valley and/or peak, CTRL.upd), never in the middle of a carrier period.
// Parameters:
//   AddrWidth - byte address width of the bus port (>= 8); addresses without a register read 0
//   MinPeriod, FreqMax, GatePol - passed to svpwm_core (GatePol is also the reset value of CTRL.pol)
//               MinPeriod defaults to the build's (svpwm_pkg::min_period(Features), as svpwm_mmio)
//   Features  - the build, a mask of svpwm_pkg::Feat* bits (default svpwm_pkg::CfgFull; svpwm_mmio):
//               registers and fields of a feature not built read 0 and ignore writes (FEATURES.features)
//   ClkHz     - the core clock in Hz, read back in CLK_HZ for host software (0 = not stated; >= 0)
//   CntWidth  - the core's carrier / period / compare width, 12..16 (default 16, the PERIOD field's);
//               a PERIOD above 2^CntWidth - 1 runs as 2^CntWidth - 1 (svpwm_mmio)
//   The other widths are fixed by the register map: PhaseWidth 34, FreqWidth 24, DtWidth 10 (change
//   rdl/svpwm.rdl and regenerate to change them).
// Latency: write: AW/W accepted -> register written 1-2 clocks later (BVALID the clock after);
//   read: AR accepted -> RVALID the next clock.
// Restrictions: values written to several registers (e.g. V1 and V2) are sampled together only if
//   all writes land between two load points; CTRL.lock and the core's lock hold until reset.
`default_nettype none

module svpwm_axil #(
  parameter int         AddrWidth = 8,                           // byte address width (>= 8)
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,          // the build (svpwm_pkg::Cfg*)
  parameter int         MinPeriod = svpwm_pkg::min_period(Features),   // svpwm_core MinPeriod
  parameter int         FreqMax   = (1 << 23) - 1,               // svpwm_core FreqMax (FreqWidth 24)
  parameter logic [1:0] GatePol   = 2'b00,                       // svpwm_core GatePol, CTRL.pol reset
  parameter int         ClkHz     = 0,                           // clock in Hz, read in CLK_HZ (0 = not stated)
  parameter int         CntWidth  = 16                           // svpwm_core CntWidth, 12..16
) (
  input  logic                 clk_i,              // core and bus clock
  input  logic                 rst_ni,             // asynchronous reset, active low
  // AXI4-Lite slave (32-bit data; AWPROT / ARPROT not used; responses always OKAY)
  input  logic [AddrWidth-1:0] axil_awaddr_i,
  input  logic                 axil_awvalid_i,
  output logic                 axil_awready_o,
  input  logic [31:0]          axil_wdata_i,
  input  logic [3:0]           axil_wstrb_i,
  input  logic                 axil_wvalid_i,
  output logic                 axil_wready_o,
  output logic [1:0]           axil_bresp_o,
  output logic                 axil_bvalid_o,
  input  logic                 axil_bready_i,
  input  logic [AddrWidth-1:0] axil_araddr_i,
  input  logic                 axil_arvalid_i,
  output logic                 axil_arready_o,
  output logic [31:0]          axil_rdata_o,
  output logic [1:0]           axil_rresp_o,
  output logic                 axil_rvalid_o,
  input  logic                 axil_rready_i,
  // inverter side
  input  logic                 fault_i,            // trip input, asynchronous, active high
  input  logic                 sync_i,             // another core's sync_o (same clock), CTRL.sync_en
  output logic [2:0]           gate_hi_o,          // {c, b, a} high-side gate pins (polarity applied)
  output logic [2:0]           gate_lo_o,          // {c, b, a} low-side gate pins (polarity applied)
  output logic [2:0]           pole_o,             // {c, b, a} modulator states before dead time
  output logic                 valley_o,           // pulse: first clock of a carrier period
  output logic                 peak_o,             // pulse: carrier peak
  output logic                 update_o,           // pulse: new compare values active from this clock
  output logic                 adc_trig_o,         // pulse: ADC trigger (CTRL.adc_trig, ADC_PT0 / ADC_PT1)
  output logic [1:0]           adc_pt_o,           // pulse: ADC trigger point k (ADC_PT0 / ADC_PT1; feature adc)
  output logic                 sync_o,             // pulse at each valley, for other cores' sync_i
  output logic                 running_o,          // gates modulating (e.g. an LED)
  output logic                 tripped_o           // safe state forced (e.g. an LED)
);

  logic                 req, we;
  logic [AddrWidth-1:0] addr;
  logic [31:0]          wdata, rdata;
  logic [3:0]           be;

  svpwm_axil_if #(
    .AddrWidth (AddrWidth)
  ) u_if (
    .clk_i (clk_i), .rst_ni (rst_ni),
    .axil_awaddr_i (axil_awaddr_i), .axil_awvalid_i (axil_awvalid_i), .axil_awready_o (axil_awready_o),
    .axil_wdata_i (axil_wdata_i), .axil_wstrb_i (axil_wstrb_i), .axil_wvalid_i (axil_wvalid_i),
    .axil_wready_o (axil_wready_o), .axil_bresp_o (axil_bresp_o), .axil_bvalid_o (axil_bvalid_o),
    .axil_bready_i (axil_bready_i), .axil_araddr_i (axil_araddr_i), .axil_arvalid_i (axil_arvalid_i),
    .axil_arready_o (axil_arready_o), .axil_rdata_o (axil_rdata_o), .axil_rresp_o (axil_rresp_o),
    .axil_rvalid_o (axil_rvalid_o), .axil_rready_i (axil_rready_i),
    .req_o (req), .we_o (we), .addr_o (addr), .wdata_o (wdata), .be_o (be), .rdata_i (rdata)
  );

  svpwm_mmio #(
    .Features (Features),
    .AddrWidth (AddrWidth), .MinPeriod (MinPeriod), .FreqMax (FreqMax), .GatePol (GatePol), .ClkHz (ClkHz),
    .CntWidth (CntWidth)
  ) u_mmio (
    .clk_i (clk_i), .rst_ni (rst_ni),
    .req_i (req), .we_i (we), .addr_i (addr), .wdata_i (wdata), .be_i (be), .rdata_o (rdata),
    .fault_i (fault_i), .sync_i (sync_i), .gate_hi_o (gate_hi_o), .gate_lo_o (gate_lo_o), .pole_o (pole_o),
    .valley_o (valley_o), .peak_o (peak_o), .update_o (update_o), .adc_trig_o (adc_trig_o),
    .adc_pt_o (adc_pt_o), .sync_o (sync_o), .running_o (running_o), .tripped_o (tripped_o)
  );

endmodule

`default_nettype wire
