//! The SPI bus the display's pixels leave on, writing through the transmit FIFO.
//!
//! `rp2040-hal`'s blocking `SpiBus::write` waits for each byte to come back before it
//! sends the next, so every byte pays its wire time and the polling on top of it. This
//! bus keeps the PL022's eight-byte transmit FIFO fed instead and drops what comes
//! back once, at the flush: the wire runs back to back and the core spends only the
//! FIFO's stores on it.
//!
//! The flush waits until the last bit has left, so a transaction of `ExclusiveDevice`
//! (which flushes before it raises CS) ends with the wire idle, and mipidsi's DC pin
//! changes only between transactions: the panel sees the same bytes with the same DC
//! as through the HAL's own write.

use core::convert::Infallible;
use embedded_hal::spi::{ErrorType, SpiBus};
use embedded_hal_nb::spi::FullDuplex;
use rp2040_hal::spi::{Enabled, Spi, SpiDevice, ValidSpiPinout};

/// An 8-bit `rp2040-hal` SPI bus whose writes fill the transmit FIFO.
pub struct FifoSpi<D: SpiDevice, P: ValidSpiPinout<D>>(pub Spi<Enabled, D, P, 8>);

impl<D: SpiDevice, P: ValidSpiPinout<D>> ErrorType for FifoSpi<D, P> {
    type Error = Infallible;
}

impl<D: SpiDevice, P: ValidSpiPinout<D>> SpiBus<u8> for FifoSpi<D, P> {
    fn read(&mut self, words: &mut [u8]) -> Result<(), Infallible> {
        self.flush()?;
        SpiBus::read(&mut self.0, words)
    }

    fn write(&mut self, words: &[u8]) -> Result<(), Infallible> {
        for &word in words {
            // Waits only while the FIFO is full; the received bytes are left in the
            // receive FIFO (full, it drops the rest: no interrupt is enabled on that).
            while FullDuplex::write(&mut self.0, word).is_err() {}
        }
        Ok(())
    }

    fn transfer(&mut self, read: &mut [u8], write: &[u8]) -> Result<(), Infallible> {
        self.flush()?;
        SpiBus::transfer(&mut self.0, read, write)
    }

    fn transfer_in_place(&mut self, words: &mut [u8]) -> Result<(), Infallible> {
        self.flush()?;
        SpiBus::transfer_in_place(&mut self.0, words)
    }

    fn flush(&mut self) -> Result<(), Infallible> {
        // The last bit on the wire, then the receive FIFO emptied, so that a read
        // after it gets its own bytes.
        while self.0.is_busy() {}
        while FullDuplex::read(&mut self.0).is_ok() {}
        Ok(())
    }
}
