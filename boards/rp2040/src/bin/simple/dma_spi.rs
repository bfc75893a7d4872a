//! The display's SPI bus, its bytes sent by DMA while the core traces on.
//!
//! mipidsi fills its pixel buffer and writes it through an `embedded-hal` `SpiDevice`;
//! a blocking write would hold the core for the buffer's wire time. Here each write is
//! copied into one of two chunk buffers and handed to a DMA channel paced by SPI1's
//! transmit request, and the write returns: the core fills the next buffer while the
//! last one is on the wire (double buffering). A write waits only for the chunk before
//! the one in flight.
//!
//! A write of a few bytes (a command, its parameters) goes straight into SPI1's
//! transmit FIFO instead, after the chunk in flight: setting up a transfer and copying
//! into a chunk costs the core more than the FIFO's eight entries take to fill.
//!
//! The DC pin ([`Dc`]) shares the bus: before it changes, the DMA transfer finishes
//! and the last bit leaves the wire, and CS goes high, so every byte reaches the panel
//! with the DC it was written with, as through `ExclusiveDevice`'s blocking writes. CS
//! stays low from a transaction's first byte until then (consecutive pixel writes are
//! one stretch of RAMWR data, which the ST7789 takes either way).

use core::cell::RefCell;
use core::convert::Infallible;
use embedded_hal::digital::{ErrorType as PinErrorType, OutputPin};
use embedded_hal::spi::{ErrorType, Operation, SpiBus, SpiDevice};
use embedded_hal_nb::spi::FullDuplex;
use rp2040_hal::dma::{single_buffer, SingleChannel};
use rp2040_hal::spi::{self as hal_spi, Enabled, Spi, ValidSpiPinout};

/// Bytes a chunk holds: mipidsi's pixel buffer (`main.rs`) is written in one chunk.
pub const CHUNK: usize = 512;

/// Writes of at most this many bytes go into the transmit FIFO (eight entries deep)
/// without DMA.
const SHORT: usize = 8;

/// A chunk buffer and how many of its bytes are to be sent.
pub struct Chunk {
    buf: &'static mut [u8; CHUNK],
    len: usize,
}

// SAFETY: the pointer and length are those of the first `len` bytes of a `'static`
// buffer (`len ≤ CHUNK`), which the transfer owns (it holds the `Chunk`) until
// `wait` gives it back; nothing else can write it meanwhile.
unsafe impl embedded_dma::ReadBuffer for Chunk {
    type Word = u8;
    unsafe fn read_buffer(&self) -> (*const u8, usize) {
        (self.buf.as_ptr(), self.len.min(CHUNK))
    }
}

impl Chunk {
    pub fn new(buf: &'static mut [u8; CHUNK]) -> Self {
        Self { buf, len: 0 }
    }
}

type Spi8<D, P> = Spi<Enabled, D, P, 8>;

/// The wire: SPI1 and the DMA channel, idle or sending a chunk.
enum Wire<CH: SingleChannel, D: hal_spi::SpiDevice, P: ValidSpiPinout<D>> {
    Idle(CH, Spi8<D, P>),
    Sending(single_buffer::Transfer<CH, Chunk, Spi8<D, P>>),
}

/// SPI1, its DMA channel, the two chunk buffers and the CS and DC pins.
pub struct Bus<CH: SingleChannel, D: hal_spi::SpiDevice, P: ValidSpiPinout<D>, CS, DC> {
    /// `None` only while a transfer is being started or waited for.
    wire: Option<Wire<CH, D, P>>,
    /// The chunk buffers not on the wire (one or two).
    free: heapless::Vec<Chunk, 2>,
    cs: CS,
    dc: DC,
}

impl<CH, D, P, CS, DC> Bus<CH, D, P, CS, DC>
where
    CH: SingleChannel,
    D: hal_spi::SpiDevice,
    P: ValidSpiPinout<D>,
    CS: OutputPin<Error = Infallible>,
    DC: OutputPin<Error = Infallible>,
{
    pub fn new(ch: CH, spi: Spi8<D, P>, chunks: [Chunk; 2], cs: CS, dc: DC) -> Self {
        Self {
            wire: Some(Wire::Idle(ch, spi)),
            free: heapless::Vec::from_iter(chunks),
            cs,
            dc,
        }
    }

    /// The transfer in flight finished (its chunk back among the free ones); the
    /// channel and SPI1, with bytes possibly still in the transmit FIFO.
    fn settle(&mut self) -> Option<(CH, Spi8<D, P>)> {
        match self.wire.take()? {
            Wire::Idle(ch, spi) => Some((ch, spi)),
            Wire::Sending(transfer) => {
                let (ch, chunk, spi) = transfer.wait();
                let _ = self.free.push(chunk);
                Some((ch, spi))
            }
        }
    }

    /// `bytes` out by DMA, a chunk at a time; returns once the last chunk is started.
    /// A short write, into the transmit FIFO once the chunk in flight is sent.
    fn write(&mut self, bytes: &[u8]) {
        let Ok(()) = self.cs.set_low();
        if bytes.len() <= SHORT {
            let Some((ch, mut spi)) = self.settle() else {
                return;
            };
            for &byte in bytes {
                let Ok(()) = embedded_hal_nb::nb::block!(FullDuplex::write(&mut spi, byte));
            }
            self.wire = Some(Wire::Idle(ch, spi));
            return;
        }
        for part in bytes.chunks(CHUNK) {
            // With at most one chunk in flight, one is free.
            let Some(mut chunk) = self.free.pop() else {
                return;
            };
            if let Some(to) = chunk.buf.get_mut(..part.len()) {
                to.copy_from_slice(part);
            }
            chunk.len = part.len();
            let Some((ch, spi)) = self.settle() else {
                return;
            };
            self.wire = Some(Wire::Sending(single_buffer::Config::new(ch, chunk, spi).start()));
        }
    }

    /// Every byte off the wire, the receive FIFO emptied, CS high: DC may change, and
    /// the panel shows everything written.
    pub fn finish(&mut self) -> Option<&mut Spi8<D, P>> {
        let (ch, mut spi) = self.settle()?;
        while spi.is_busy() {}
        while FullDuplex::read(&mut spi).is_ok() {}
        let Ok(()) = self.cs.set_high();
        self.wire = Some(Wire::Idle(ch, spi));
        match &mut self.wire {
            Some(Wire::Idle(_, spi)) => Some(spi),
            _ => None,
        }
    }
}

/// The bus as mipidsi's `SpiDevice`.
pub struct Device<'a, B>(pub &'a RefCell<B>);

/// The bus's DC pin as mipidsi's data/command pin.
pub struct Dc<'a, B>(pub &'a RefCell<B>);

impl<B> ErrorType for Device<'_, B> {
    type Error = Infallible;
}

impl<CH, D, P, CS, DC> SpiDevice for Device<'_, Bus<CH, D, P, CS, DC>>
where
    CH: SingleChannel,
    D: hal_spi::SpiDevice,
    P: ValidSpiPinout<D>,
    CS: OutputPin<Error = Infallible>,
    DC: OutputPin<Error = Infallible>,
{
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        // One borrower at a time: mipidsi calls the device and the pin in turn.
        let Ok(mut bus) = self.0.try_borrow_mut() else {
            return Ok(());
        };
        for op in operations {
            match op {
                Operation::Write(bytes) => bus.write(bytes),
                // mipidsi only writes; the rest blocking, after the writes before.
                Operation::Read(words) => {
                    if let Some(spi) = bus.finish() {
                        let Ok(()) = SpiBus::read(spi, words);
                    }
                }
                Operation::Transfer(read, write) => {
                    if let Some(spi) = bus.finish() {
                        let Ok(()) = SpiBus::transfer(spi, read, write);
                    }
                }
                Operation::TransferInPlace(words) => {
                    if let Some(spi) = bus.finish() {
                        let Ok(()) = SpiBus::transfer_in_place(spi, words);
                    }
                }
                Operation::DelayNs(_) => {}
            }
        }
        Ok(())
    }
}

impl<B> PinErrorType for Dc<'_, B> {
    type Error = Infallible;
}

impl<CH, D, P, CS, DC> OutputPin for Dc<'_, Bus<CH, D, P, CS, DC>>
where
    CH: SingleChannel,
    D: hal_spi::SpiDevice,
    P: ValidSpiPinout<D>,
    CS: OutputPin<Error = Infallible>,
    DC: OutputPin<Error = Infallible>,
{
    fn set_low(&mut self) -> Result<(), Infallible> {
        if let Ok(mut bus) = self.0.try_borrow_mut() {
            bus.finish();
            bus.dc.set_low()?;
        }
        Ok(())
    }

    fn set_high(&mut self) -> Result<(), Infallible> {
        if let Ok(mut bus) = self.0.try_borrow_mut() {
            bus.finish();
            bus.dc.set_high()?;
        }
        Ok(())
    }
}
